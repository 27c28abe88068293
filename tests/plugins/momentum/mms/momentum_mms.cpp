// TEST ONLY plugin for the momentum plugin's tests: it stands in for the hamiltonian, lapse and hydro
// plugins. It publishes a "star" Fluid (moving, sigma from its parameter), registers and fills
// chi, eta, puncture_phi analytically on every level and the fluid fields (rho0, press = 0,
// enthalpy = 1, fluid_velocity) so that the momentum density is the J of mms/problem.hpp, for which
// W_exact solves eq. mom_ansatz_hat exactly. At ANALYSIS it reports the error of the solved wvec.
// With `omit` it leaves out one of chi, eta, puncture_phi, to test momentum's refusal.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "../../../support/test_fluid.hpp"
#include "problem.hpp"

namespace bhnsid::momentum::test {
namespace {

using core::Bin;
using core::Context;
using core::TensorKind;

struct State {
  std::shared_ptr<bhnsid::test::FieldVelocityFluid> fluid = std::make_shared<bhnsid::test::FieldVelocityFluid>();
  Problem problem;
};

template <class Fn>
void for_points(const Level& lv, Fn&& fn) {
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) fn(lv.at(i, j, k), Vec3{lv.x(i), lv.y(j), lv.z(k)});
}

void fill(Grid& grid, const bhnsid::test::FieldVelocityFluid& fluid, const Problem& problem, double scale,
          const std::string& omit) {
  const std::vector<TensorKind> scalar{TensorKind::scalar};
  const int chi = omit == "chi" ? -1 : grid.add_field(fields::chi, scalar);
  const int eta = omit == "eta" ? -1 : grid.add_field(fields::eta, scalar);
  const int pphi = omit == "puncture_phi" ? -1 : grid.add_field(fields::puncture_phi, scalar);
  grid.add_field(fields::alpha, scalar);
  const auto [rho0, press, enthalpy, vel] = fluid.attach(grid);
  double max_v2 = 0;
  for (int l = 0; l < grid.num_levels(); ++l) {
    const Level& lv = grid.level(l);
    double *c = chi >= 0 ? grid.data(chi, 0, l) : nullptr, *e = eta >= 0 ? grid.data(eta, 0, l) : nullptr,
           *p = pphi >= 0 ? grid.data(pphi, 0, l) : nullptr;
    double *r = grid.data(rho0, 0, l), *pr = grid.data(press, 0, l), *h = grid.data(enthalpy, 0, l);
    double* v[3] = {grid.data(vel, 0, l), grid.data(vel, 1, l), grid.data(vel, 2, l)};
    for_points(lv, [&](std::ptrdiff_t idx, const Vec3& x) {
      if (c) c[idx] = problem.chi(x).value;
      if (e) e[idx] = problem.eta(x).value;
      if (p) p[idx] = problem.puncture_phi;
      // The solver restricts the fluid fields from the finest level; filled on every level anyway.
      const Problem::Fluid f = problem.fluid(x, scale);
      r[idx] = f.rho0;
      pr[idx] = 0.0;
      h[idx] = 1.0;
      for (int a = 0; a < 3; ++a) v[a][idx] = f.velocity[a];
      max_v2 = std::max(max_v2, f.v2);
    });
    for (int id : {chi, eta, pphi, rho0, press, enthalpy, vel})
      if (id >= 0) grid.fill_ghosts(id, l);
  }
  if (!(max_v2 < 1))
    throw core::InputError(fmt::format("momentum_mms.velocity_scale = {}: the fluid is superluminal (v^2 = {})", scale, max_v2));
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("grid");
  b.implements("star");
  b.implements("lapse");
  b.real("sigma").doc("the Fluid's sigma (multiplies the matter term by sigma^2)").default_value(0.8).greater_than(0);
  b.real("velocity_scale")
      .doc("V = velocity_scale * J; rho0 = alpha (1 - v^2) / velocity_scale then carries J (max v^2 about 0.3 at 0.02)")
      .default_value(0.02)
      .greater_than(0);
  b.real("chi_amplitude").doc("chi = 1 + chi_amplitude G (0: no chi gradient term)").default_value(0.3);
  b.real("eta_amplitude").doc("eta = 1 + eta_amplitude G (0: no eta gradient term)").default_value(-0.25).greater_than(-1);
  b.real("puncture_phi")
      .doc("the constant stand-in for puncture_phi, so that phi = puncture_phi + chi differs from chi; 0 makes the "
           "configuration a physical one (gamma = chi^4 delta), which the ire plugin can check")
      .default_value(0.1)
      .at_least(0);
  b.keyword("omit", {"none", "chi", "eta", "puncture_phi"})
      .doc("leave one field out, to test the momentum plugin's refusal")
      .default_value(std::string("none"));

  b.schedule(Bin::startup, "publish", [state](Context& ctx) {
     state->problem.sigma = ctx.params().real("sigma");
     state->problem.puncture_phi = ctx.params().real("puncture_phi");
     state->problem.chi_bump.amp = ctx.params().real("chi_amplitude");
     state->problem.eta_bump.amp = ctx.params().real("eta_amplitude");
     state->fluid->sigma_value = state->problem.sigma;
     ctx.publish<bhnsid::Fluid>("star", state->fluid);
     ctx.publish<bhnsid::Lapse>("lapse", std::make_shared<bhnsid::test::EtaOverPhiLapse>());
   }).doc("publish the test Fluid and the lapse alpha = eta/phi (its regular part eta is the momentum weight)");

  // Named "setup": as the stand-in "lapse" it is the entry that momentum orders itself after.
  b.schedule(Bin::setup, "setup", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     fill(grid, *state->fluid, state->problem, ctx.params().real("velocity_scale"), ctx.params().string("omit"));
   })
      .before("equation.momentum.setup")
      .doc("chi, eta, puncture_phi and the fluid fields on every level");

  b.schedule(Bin::analysis, "errors", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     const int w = grid.field_id(fields::wvec);
     const Level& lv = grid.finest();
     double max_error = 0, sum = 0, count = 0, max_exact = 0;
     for_points(lv, [&](std::ptrdiff_t idx, const Vec3& x) {
       const Vec3 exact = state->problem.exact(x);
       for (int a = 0; a < 3; ++a) {
         const double d = grid.data(w, a, 0)[idx] - exact[static_cast<std::size_t>(a)];
         max_error = std::max(max_error, std::fabs(d));
         max_exact = std::max(max_exact, std::fabs(exact[static_cast<std::size_t>(a)]));
         sum += d * d;
         count += 1;
       }
     });
     ctx.set_scalar("w_error_max", max_error);
     ctx.set_scalar("w_error_rms", std::sqrt(sum / count));
     ctx.set_scalar("w_exact_max", max_exact);
     ctx.log().info("W - W_exact: max {:.3e}, rms {:.3e} (max |W_exact| = {:.3f})", max_error, std::sqrt(sum / count),
                    max_exact);
   }).doc("w_error_max, w_error_rms: wvec against W_exact on the finest level");
}

}  // namespace
}  // namespace bhnsid::momentum::test

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "momentum_mms", "0.1",
                                     "TEST ONLY: chi, eta, fluid and the J of a manufactured W for the momentum plugin",
                                     &bhnsid::momentum::test::declare};
  return &info;
}
