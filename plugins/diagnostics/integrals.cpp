#include "integrals.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "faces.hpp"

namespace bhnsid::diagnostics {

namespace {

const double* field(const Grid& grid, const char* name, int component = 0) {
  return grid.has_field(name) ? grid.data(grid.field_id(name), component, 0) : nullptr;
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
  const double* rho0 = field(grid, fields::rho0);
  const double* press = field(grid, fields::press);
  const double* enthalpy = field(grid, fields::enthalpy);
  const double* eta = field(grid, fields::eta);
  const double* vel[3] = {field(grid, fields::fluid_velocity, 0), field(grid, fields::fluid_velocity, 1),
                          field(grid, fields::fluid_velocity, 2)};
  const double* shift[3] = {field(grid, fields::shift, 0), field(grid, fields::shift, 1), field(grid, fields::shift, 2)};
  if (in.moving && !eta)
    throw core::RunFailure("diagnostics: moving matter needs eta (the lapse plugin) for its Lorentz factor");
  std::vector<double> rest(lv.size, 0.0), energy(lv.size, 0.0);
  const double s2 = in.sigma * in.sigma;
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        const double phi = (punc ? punc[p] : 0.0) + chi[p];
        const double phi2 = phi * phi, phi4 = phi2 * phi2;
        double e = aa ? aa[p] / (16.0 * std::numbers::pi * phi4 * phi2 * phi) : 0.0;
        if (rho0 && rho0[p] > 0) {
          double lorentz2 = 1.0;
          if (in.moving) {
            double u[3];
            for (int c = 0; c < 3; ++c)
              u[c] = vel[c][p] + (shift[c] ? shift[c][p] : 0.0);
            lorentz2 = lorentz_squared(phi, eta[p], u[0], u[1], u[2]);
          }
          e += s2 * phi4 * phi * matter_projections(rho0[p], press[p], enthalpy[p], lorentz2).energy;
          rest[p] = rho0[p] * std::sqrt(lorentz2) * phi4 * phi2;
        }
        energy[p] = e;
      }
  Masses m;
  m.rest_mass = in.sigma * s2 * grid.integrate(rest.data(), Parity{}, 0);
  m.adm_mass_volume = in.sigma * (in.bh_bare_mass + grid.integrate(energy.data(), Parity{}, 0));
  m.adm_mass_falloff = in.sigma * (in.bh_bare_mass + 2.0 * falloff_coefficient(grid, chi, in.centre));
  return m;
}

}  // namespace bhnsid::diagnostics
