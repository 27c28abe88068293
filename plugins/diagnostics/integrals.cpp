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
  const double* matter = in.matter ? field(grid, fields::matter_energy) : nullptr;
  if (in.matter && !matter)
    throw core::RunFailure("diagnostics: a fluid without the matter_energy field (rho_E); the star registers it");
  const double sigma2 = in.sigma * in.sigma;
  // Every point but the ghost plane is written below (integrate reads no ghost); uninitialised,
  // so that the pages are first touched by the parallel loop instead of a serial zero fill.
  const auto energy = std::make_unique_for_overwrite<double[]>(lv.size);
  // Per row, the matter switch compile-time, so that the loop vectorises; rho_E is 0 outside the
  // matter (the star writes it so).
  auto densities = [&](auto with_matter) {
    for_stored_points(lv, [&](std::ptrdiff_t p) {
      const double phi = (punc ? punc[p] : 0.0) + chi[p];
      const double phi2 = phi * phi, phi4 = phi2 * phi2;
      double e = aa ? aa[p] / (16.0 * std::numbers::pi * phi4 * phi2 * phi) : 0.0;
      if constexpr (decltype(with_matter)::value) e += sigma2 * phi4 * phi * matter[p];
      energy[static_cast<std::size_t>(p)] = e;
    });
  };
  if (matter)
    densities(std::true_type{});
  else
    densities(std::false_type{});
  Masses m;
  m.adm_mass_volume = in.sigma * (in.bh_bare_mass + grid.integrate(energy.get(), Parity{}, 0));
  m.adm_mass_falloff = in.sigma * (in.bh_bare_mass + 2.0 * falloff_coefficient(grid, chi, in.centre));
  return m;
}

}  // namespace bhnsid::diagnostics
