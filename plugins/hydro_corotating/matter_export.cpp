// HydroBase's variables from the corotating star: rho0, P and eps from the EOS at the stored rho0
// (so the three are consistent to round-off), the Valencia velocity v^i = (beta^i + Omegahat xi^i)/alpha
// and W (kinematics.hpp) inside the star; outside it the vacuum values rho = P = eps = 0, v = 0,
// W = 1 (the corotating velocity is superluminal far out, and means nothing where there is no fluid).
#include "matter_export.hpp"

#include <fmt/format.h>

#include <cmath>

#include "bhnsid/core/errors.hpp"

#include "kinematics.hpp"

namespace bhnsid::hydro_corotating {

namespace {

enum class Quantity { rho, press, eps, vel_x, vel_y, vel_z, lorentz };

void fill(Grid& grid, const Eos& eos, const Lapse& lapse, const StarFluid& fluid, Quantity q, double* out) {
  const Level& lv = grid.finest();
  const double* rho0 = grid.data(grid.field_id(fields::rho0), 0, 0);
  const double* chi = grid.data(grid.field_id(fields::chi), 0, 0);
  const double* lapse_alpha = lapse_on(grid, lapse, 0);
  const double* pphi = grid.data(grid.field_id(fields::puncture_phi), 0, 0);
  const double* beta[3] = {nullptr, nullptr, nullptr};
  if (grid.has_field(fields::shift))
    for (int c = 0; c < 3; ++c) beta[c] = grid.data(grid.field_id(fields::shift), c, 0);
  const double w = fluid.omega_hat();
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        const double r = rho0[p];
        if (!(r > 0)) {
          out[p] = q == Quantity::lorentz ? 1.0 : 0.0;
          continue;
        }
        // U = beta + Omegahat xi, xi = (-yhat, xhat, 0): the same in hatted and physical units.
        double u[3] = {-w * lv.y(j), w * lv.x(i), 0.0};
        for (int c = 0; c < 3; ++c) u[c] += beta[c] ? beta[c][p] : 0.0;
        const double phi = pphi[p] + chi[p], alpha = lapse_alpha[p];
        // Matter where no observer is at rest (alpha <= 0, inside a horizon) has no Eulerian velocity.
        if (!(alpha > 0))
          throw core::RunFailure(fmt::format("hydro_corotating: matter (rho0 = {:.6g}) at xhat = ({:.6g}, {:.6g}, {:.6g}) "
                                             "where the lapse alpha = {:.6g} is not positive: no velocity to write",
                                             r, lv.x(i), lv.y(j), lv.z(k), alpha));
        switch (q) {
          case Quantity::rho: out[p] = r; break;
          case Quantity::press: out[p] = eos.pressure(r); break;
          case Quantity::eps: out[p] = eos.specific_internal_energy(r); break;
          case Quantity::vel_x: out[p] = u[0] / alpha; break;
          case Quantity::vel_y: out[p] = u[1] / alpha; break;
          case Quantity::vel_z: out[p] = u[2] / alpha; break;
          case Quantity::lorentz: out[p] = std::sqrt(lorentz_squared(phi, alpha, u[0], u[1], u[2])); break;
        }
      }
}

}  // namespace

std::shared_ptr<FieldExport> matter_export(Grid& grid, const Eos& eos, const Lapse& lapse, const StarFluid& fluid) {
  auto out = std::make_shared<FieldExportList>();
  struct Entry {
    const char* name;
    const char* units;
    Quantity q;
    int z_parity;
    const char* doc;
  };
  const Entry entries[] = {
      {"rho", "mass/length^3", Quantity::rho, 1, "rest-mass density rho0 (never rescaled by sigma); 0 outside the star"},
      {"press", "mass/length^3", Quantity::press, 1, "pressure P(rho0) of the EOS; 0 outside the star"},
      {"eps", "1", Quantity::eps, 1, "specific internal energy eps(rho0) of the EOS; 0 outside the star"},
      {"vel[0]", "1", Quantity::vel_x, 1, "Valencia velocity v^x = (beta^x + Omega xi^x)/alpha; 0 outside the star"},
      {"vel[1]", "1", Quantity::vel_y, 1, "Valencia velocity v^y = (beta^y + Omega xi^y)/alpha; 0 outside the star"},
      {"vel[2]", "1", Quantity::vel_z, -1, "Valencia velocity v^z = beta^z/alpha; 0 outside the star"},
      {"w_lorentz", "1", Quantity::lorentz, 1, "Lorentz factor W = (1 - phi^4 v^2)^(-1/2); 1 outside the star"},
  };
  Grid* g = &grid;
  const Eos* e = &eos;
  const StarFluid* f = &fluid;
  const Lapse* a = &lapse;
  for (const Entry& entry : entries)
    out->add({"HydroBase", entry.name, entry.units, Parity{entry.z_parity, 1}, entry.doc},
             [g, e, a, f, q = entry.q](double* values) { fill(*g, *e, *a, *f, q, values); });
  return out;
}

}  // namespace bhnsid::hydro_corotating
