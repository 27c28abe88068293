// HydroBase's variables from the star: rho0, P and eps from the EOS at the stored rho0 (so the three
// are consistent to round-off), the Valencia velocity v^i and W from the flow inside the star; outside
// it the vacuum values rho = P = eps = 0, v = 0, W = 1 (a flow's velocity means nothing where there is
// no fluid, and the corotating one is superluminal far out).
#include "matter_export.hpp"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <string>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::star {

namespace {

enum class Quantity { rho, press, eps, vel_x, vel_y, vel_z, lorentz };

void fill(Grid& grid, const Eos& eos, const StarFluid& fluid, Quantity q, double* out) {
  const Level& lv = grid.finest();
  const double* rho0 = grid.data(grid.field_id(fields::rho0), 0, 0);
  if (q == Quantity::rho || q == Quantity::press || q == Quantity::eps) {
    for_stored_points(lv, [&](std::ptrdiff_t p) {
      const double r = rho0[p];
      out[p] = !(r > 0) ? 0.0 : q == Quantity::rho ? r : q == Quantity::press ? eos.pressure(r) : eos.specific_internal_energy(r);
    });
    return;
  }
  const auto lorentz = std::make_unique_for_overwrite<double[]>(lv.size);
  std::unique_ptr<double[]> v[3];
  double* vp[3];
  for (int c = 0; c < 3; ++c) {
    v[c] = std::make_unique_for_overwrite<double[]>(lv.size);
    vp[c] = v[c].get();
  }
  fluid.flow().velocity(grid, fluid.flow_constants(), lorentz.get(), vp);
  const double* src = q == Quantity::lorentz ? lorentz.get() : vp[static_cast<int>(q) - static_cast<int>(Quantity::vel_x)];
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        // Matter without a timelike velocity (inside a horizon, beyond a light cylinder) has none to write.
        if (!std::isfinite(lorentz[p]))
          throw core::RunFailure(fmt::format("star: matter (rho0 = {:.6g}) at xhat = ({:.6g}, {:.6g}, {:.6g}) has no "
                                             "timelike {} velocity: nothing to write ({})",
                                             rho0[p], lv.x(i), lv.y(j), lv.z(k), fluid.flow().kind(),
                                             fluid.flow().acausal_matter(grid, fluid.flow_constants())));
        out[p] = src[p];
      }
}

}  // namespace

std::shared_ptr<FieldExport> matter_export(Grid& grid, const Eos& eos, const StarFluid& fluid) {
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
      {"vel[0]", "1", Quantity::vel_x, 1, "Valencia velocity v^x of the flow (corotating: (beta^x + Omega xi^x)/alpha); 0 outside the star"},
      {"vel[1]", "1", Quantity::vel_y, 1, "Valencia velocity v^y of the flow (corotating: (beta^y + Omega xi^y)/alpha); 0 outside the star"},
      {"vel[2]", "1", Quantity::vel_z, -1, "Valencia velocity v^z of the flow (corotating: beta^z/alpha); 0 outside the star"},
      {"w_lorentz", "1", Quantity::lorentz, 1, "Lorentz factor W = (1 - phi^4 v^2)^(-1/2); 1 outside the star"},
  };
  Grid* g = &grid;
  const Eos* e = &eos;
  const StarFluid* f = &fluid;
  for (const Entry& entry : entries)
    out->add({"HydroBase", entry.name, entry.units, Parity{entry.z_parity, 1}, entry.doc},
             [g, e, f, q = entry.q](double* values) { fill(*g, *e, *f, q, values); });
  return out;
}

}  // namespace bhnsid::star
