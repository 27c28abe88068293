#include "integrals.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <type_traits>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "faces.hpp"

namespace bhnsid::diagnostics {

namespace {

const double* field(const Grid& grid, const char* name) {
  return grid.has_field(name) ? grid.data(grid.field_id(name), 0, 0) : nullptr;
}

/// Solid-angle-weighted mean of rhat (chi - 1) over the outer faces.
double falloff_coefficient(const Grid& grid, const double* chi, std::array<double, 3> c) {
  const Level& lv = grid.finest();
  double sum = 0, weights = 0;
  for_each_face_point(lv, [&](int axis, double, int i, int j, int k, double area) {
    const double d[3] = {lv.x(i) - c[0], lv.y(j) - c[1], lv.z(k) - c[2]};
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double w = area * std::fabs(d[axis]) / (r * r * r);  // the solid angle the point sees
    sum += w * r * (chi[lv.at(i, j, k)] - 1.0);
    weights += w;
  });
  return sum / weights;
}

}  // namespace

Masses masses(const Grid& grid, const Inputs& in) {
  const Level& lv = grid.finest();
  const double* chi = field(grid, fields::chi);
  const double* punc = field(grid, fields::puncture_phi);
  const double* aa = field(grid, fields::aa);
  const double* eta = field(grid, fields::eta);
  if (in.moving && !eta)
    throw core::RunFailure("diagnostics: moving matter needs eta (the lapse plugin) for its Lorentz factor");
  const MatterArrays mat = matter_arrays(grid, in.sigma, in.moving, 0);
  // Every point but the ghost plane is written below (integrate reads no ghost); uninitialised,
  // so that the pages are first touched by the parallel loop instead of a serial zero fill.
  const auto energy = std::make_unique_for_overwrite<double[]>(lv.size);
  const auto rest = std::make_unique_for_overwrite<double[]>(in.matter ? lv.size : 0);
  // Per row, the matter term selected where rho0 > 0 (not branched on) and the switches
  // compile-time, so that the loop vectorises.
  auto densities = [&](auto matter, auto moving) {
    constexpr bool Matter = decltype(matter)::value, Moving = decltype(moving)::value;
#pragma omp parallel for schedule(static)
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j) {
        const std::ptrdiff_t p0 = lv.at(0, j, k);
#pragma omp simd
        for (std::ptrdiff_t p = p0; p < p0 + lv.nx; ++p) {
          const double phi = (punc ? punc[p] : 0.0) + chi[p];
          const double phi2 = phi * phi, phi4 = phi2 * phi2;
          double e = aa ? aa[p] / (16.0 * std::numbers::pi * phi4 * phi2 * phi) : 0.0;
          if constexpr (Matter) {
            double lorentz2 = 1.0;
            if constexpr (Moving)
              lorentz2 = lorentz_squared(phi, eta[p], mat.coordinate_velocity(0, p), mat.coordinate_velocity(1, p),
                                         mat.coordinate_velocity(2, p));
            const bool in_matter = mat.rho0[p] > 0;
            const double e_matter =
                mat.sigma2 * phi4 * phi * matter_projections(mat.rho0[p], mat.press[p], mat.enthalpy[p], lorentz2).energy;
            e += in_matter ? e_matter : 0.0;
            rest[static_cast<std::size_t>(p)] = in_matter ? mat.rho0[p] * std::sqrt(lorentz2) * phi4 * phi2 : 0.0;
          }
          energy[static_cast<std::size_t>(p)] = e;
        }
      }
  };
  if (!in.matter)
    densities(std::false_type{}, std::false_type{});
  else if (in.moving)
    densities(std::true_type{}, std::true_type{});
  else
    densities(std::true_type{}, std::false_type{});
  Masses m;
  m.rest_mass = in.matter ? in.sigma * mat.sigma2 * grid.integrate(rest.get(), Parity{}, 0) : 0.0;
  m.adm_mass_volume = in.sigma * (in.bh_bare_mass + grid.integrate(energy.get(), Parity{}, 0));
  m.adm_mass_falloff = in.sigma * (in.bh_bare_mass + 2.0 * falloff_coefficient(grid, chi, in.centre));
  return m;
}

}  // namespace bhnsid::diagnostics
