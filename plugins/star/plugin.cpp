// The star plugin (implements "star"): the star's density from the first integral of its flow (the
// relativistic Bernoulli equation) and the outer iteration for (sigma, Omegahat, C_B) in the core's
// SOLVE/UPDATE/CHECK loop. How the fluid moves is the "flow" capability's (flow_corotating,
// flow_irrotational): the star reads W, v^i, the projections and the first integral through it.
#include <fmt/format.h>

#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/flow.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "matter_export.hpp"
#include "spin.hpp"
#include "star.hpp"

namespace bhnsid::star {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::shared_ptr<StarFluid> fluid = std::make_shared<StarFluid>();
  std::unique_ptr<Star> star;
};

StarSettings settings_from(const core::ParamSection& p) {
  StarSettings s;
  s.rho_max = p.real("rho_max");
  s.x_a = p.real("x_a");
  s.sigma_guess = p.real("sigma_guess");
  s.model_hole_delta = p.real("model_hole_delta");
  s.tolerance = p.real("tolerance");
  s.iterate = p.boolean("iterate");
  s.test_omega_hat = p.real("test_omega_hat");
  return s;
}

std::string history_table(const Star& star) {
  std::string out = "# iteration\tsigma\tomega_hat\tbernoulli_constant\tx_c\tchange\tmatter_points\tstep_fraction\n";
  for (const StepReport& r : star.history())
    out += fmt::format("{}\t{:.15e}\t{:.15e}\t{:.15e}\t{:.15e}\t{:.6e}\t{}\t{}\n", r.iteration, r.after.sigma,
                       r.after.omega_hat, r.after.bernoulli, r.after.x_c, r.change, r.matter_points, r.fraction);
  return out;
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("grid");
  b.require("eos");
  b.require("tov_family");
  b.require("equation.hamiltonian");
  b.require("lapse");
  b.require("flow");
  b.implements("star");
  b.implements("export.star");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability)) {
      layout->estimate_fields(m, ctx.plugin(), fields::fluid_sizes);
      // The star's update holds the lapse, the conformal factor, their modelled values and the
      // enthalpy on the finest level in scratch arrays.
      m.add(ctx.plugin(), "scratch", fmt::format("five finest-level scratch arrays at {}", layout->describe()),
            5 * layout->field_bytes(core::Storage::finest_only));
    }
  });

  b.real("rho_max")
      .doc("maximum rest-mass density (rho0)_max of the star, a fixed input (code units, K = 1)")
      .required(0.1)
      .greater_than(0)
      .steerable();
  b.real("x_a")
      .doc("hatted x of the star's inner surface point xhat_A (the outer one is xhat = 1); -1 centres the star at the "
           "origin (physics-notes §9 T1)")
      .default_value(-1.0)
      .at_least(-1.0)
      .less_than(1.0);
  b.real("model_hole_delta")
      .doc("share of the hole's delta = Mhat_BH/(2 dhat) in the sigma-model's sigma (1 + delta)^2 (physics-notes §4.5); "
           "halved, then 0, when the Newton solve fails with it. Shapes the path, not the fixed point")
      .default_value(1.0)
      .at_least(0)
      .at_most(1);
  b.real("sigma_guess").doc("initial sigma; 0: R_iso(rho_max) / Rhat with Rhat = (1 - x_a)/2 (physics-notes §4.7)").default_value(0.0).at_least(0);
  b.real("tolerance")
      .doc("converged when the relative changes of sigma, C_B (and Omegahat with a black hole) of an outer step and of M0 "
           "in the last reset are below this (the paper: 1e-4)")
      .default_value(1e-6)
      .greater_than(0);
  b.real("test_omega_hat")
      .doc("TEST ONLY: Omegahat held through the run of a single star (no black hole), so that a flow's response to "
           "rotation can be tested (a corotating star spins up, an irrotational one stays static); 0 for physics")
      .default_value(0.0)
      .at_least(0);
  b.boolean("iterate")
      .doc("false: keep the initial TOV density and sigma_guess (one fixed-source field solve, for tests)")
      .default_value(true);

  b.schedule(Bin::startup, "publish", [state](Context& ctx) { ctx.publish<Fluid>("star", state->fluid); })
      .doc("publish the fluid (sigma, centre) for the equations; its values are set in SETUP");

  b.schedule(Bin::setup, "setup", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     require_single_box(grid, ctx.plugin());
     const auto& eos = ctx.services().get<Eos>("eos");
     const auto& family = ctx.services().get<TovFamily>("tov_family");
     auto& flow = ctx.services().get<Flow>("flow");
     state->star = std::make_unique<Star>(grid, eos, family, ctx.services().get<Lapse>("lapse"), flow,
                                          settings_from(ctx.params()), state->fluid, ctx.services().find<Puncture>("puncture"));
     ctx.publish<FieldExport>("export.star", matter_export(grid, eos, *state->fluid));
     const StarConstants& c = state->fluid->constants;
     ctx.log().info("{} star, {}: rho_max = {}, xhat_C = {}, Rhat = {}, initial sigma = {:.9g}, C_B = {:.9g}", flow.kind(),
                    eos.describe(), ctx.params().real("rho_max"), c.x_c, state->star->rhat_star(), c.sigma, c.bernoulli);
   })
      .after("equation.hamiltonian.setup")
      .after("lapse.setup")
      .after("tov_family.publish_family")
      .doc("TOV star of rho_max, initial sigma and C_B, fluid fields; publish the export of rho, press, eps, vel, "
           "w_lorentz");

  b.schedule(Bin::initial, "initial_data", [state](Context&) { state->star->set_initial(); })
      .after("equation.hamiltonian.initial_data")
      .after("lapse.initial_data")
      .doc("TOV initial guess: rho0, chi = psi_TOV, the lapse's regular part = alpha_TOV psi_TOV about xhat_C");

  b.checkpoint([state](Context&, core::CheckpointWriter& out) { state->star->save(out); },
               [state](Context&, const core::CheckpointReader& in) { state->star->restore(in); });
  b.warm_start([state](Context&, const core::CheckpointReader& in) { state->star->warm_start(in); });

  b.schedule(Bin::update, "outer_step", [state](Context& ctx) {
     const StepReport r = state->star->step(ctx.step_fraction());
     if (!r.model_note.empty()) ctx.log().warn("star (outer step {}): {}", r.iteration, r.model_note);
     ctx.show_progress("sigma", r.after.sigma);
     if (r.after.omega_hat != 0) ctx.show_progress("omega_hat", r.after.omega_hat);
     ctx.show_progress("bernoulli_constant", r.after.bernoulli);
     ctx.show_progress("star_rest_mass", state->fluid->rest_mass());
     ctx.show_progress("star_change", r.change);
     ctx.log().detail("outer step {}: sigma = {:.12g}, Omegahat = {:.9g}, C_B = {:.12g}, xhat_C = {:.6g}, change {:.3e}{}{}",
                    r.iteration, r.after.sigma, r.after.omega_hat, r.after.bernoulli, r.after.x_c, r.change,
                    r.fraction < 1 ? fmt::format(" ({} of the Newton step)", r.fraction) : "",
                    r.converged ? " (converged)" : "");
   }).doc("the flow's own solve (a velocity potential), Newton solve for (sigma, Omegahat, C_B) with the TOV "
          "sigma-model, reset of rho0 by the flow's first integral, flood fill; after a retreat the constants move only "
          "the run's step fraction of the Newton step");

  b.schedule(Bin::retreat, "undo_step", [state](Context& ctx) {
     state->star->retreat();
     const StarConstants& c = state->fluid->constants;
     ctx.log().detail("star: back at sigma = {:.12g}, Omegahat = {:.9g}, C_B = {:.12g}", c.sigma, c.omega_hat,
                      c.bernoulli);
   }).doc("the star's constants back to before its last outer step (UPDATE then resets the density with a shorter step)");

  b.check("star_converged", [state](Context&) {
     const auto& h = state->star->history();
     const bool done = !h.empty() && h.back().converged;
     return core::Convergence{done, h.empty() ? "" : fmt::format("star change {:.3e}", h.back().change)};
   }).doc("the last outer step changed sigma and C_B by less than the tolerance");

  b.schedule(Bin::analysis, "report", [state](Context& ctx) {
     const StarConstants& c = state->fluid->constants;
     ctx.set_scalar("sigma", c.sigma);
     ctx.set_scalar("bernoulli_constant", c.bernoulli);
     ctx.set_scalar("x_c", c.x_c);
     ctx.set_scalar("omega_hat", c.omega_hat);
     ctx.set_scalar("star_center_x_hat", c.x_c);
     ctx.set_scalar("rho_max", ctx.params().real("rho_max"));
     ctx.set_scalar("x_a", ctx.params().real("x_a"));
     ctx.set_scalar("outer_iterations", static_cast<double>(state->star->history().size()));
     if (ctx.services().get<Grid>("grid").has_field(fields::matter_momentum)) {
       const Spin s = star_spin(ctx.services().get<Grid>("grid"), *state->fluid);
       ctx.set_scalar("star_spin", s.spin);
       ctx.set_scalar("star_momentum_y", s.momentum_y);
       ctx.set_scalar("star_centroid_x", s.centroid_x);
     }
     const auto& h = state->star->history();
     ctx.log().info("star: sigma = {:.9g}, Omegahat = {:.9g}, C_B = {:.9g}, xhat_C = {:.6g} (rho_max = {}, xhat_A = {}); "
                    "{} outer steps, the last changing sigma, Omegahat, C_B and M0 by {:.2e} (tolerance {:.1e})",
                    c.sigma, c.omega_hat, c.bernoulli, c.x_c, ctx.params().real("rho_max"), ctx.params().real("x_a"),
                    h.size(), h.empty() ? 0.0 : h.back().change, ctx.params().real("tolerance"));
   }).doc("sigma, bernoulli_constant, omega_hat, x_c (star_center_x_hat), rho_max, x_a, outer_iterations; star_spin "
          "(the star's angular momentum about its rest-mass centroid, spin.hpp), star_momentum_y, star_centroid_x "
          "(physical units); one log line");

  b.schedule(Bin::output, "write", [state](Context& ctx) {
     if (!state->star) return;
     ctx.write_output("star_axis.tsv", state->star->axis_table());
     ctx.write_output("star_history.tsv", history_table(*state->star));
   }).doc("star_axis.tsv (fields and TOV values on the x axis) and star_history.tsv, also after a failure");
}

}  // namespace
}  // namespace bhnsid::star

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "star", "0.1",
                                     "the star: its density from the flow's first integral and the (sigma, Omegahat, C_B) "
                                     "outer iteration",
                                     &bhnsid::star::declare};
  return &info;
}
