// The horizon plugin (implements "horizon"): the apparent horizon about the puncture, its area and
// irreducible mass M_irr = sqrt(A/16 pi), coordinate radii and quasi-local spin (finder.hpp), in
// ANALYSIS and, on request, after every outer iteration's solve. No horizon found is a RunFailure
// naming why: the mass the user asked for is never a guess.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/horizon.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "tracker.hpp"

namespace bhnsid::horizon {
namespace {

using core::Bin;
using core::Context;

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("grid");
  b.require("puncture");
  b.require("equation.hamiltonian");
  b.implements("horizon");
  b.integer("l_max").doc("the surface's spherical harmonics up to this degree").default_value(std::int64_t{8}).at_least(2).at_most(24);
  b.real("tolerance")
      .doc("Newton stops when the largest coefficient step is below this times the mean radius")
      .default_value(1e-10)
      .greater_than(0)
      .at_most(1e-2);
  b.integer("max_iterations").doc("Newton steps before the search is declared failed").default_value(std::int64_t{40}).at_least(1);
  b.real("initial_radius")
      .doc("radius of the starting sphere about the puncture (hatted); 0: Mhat_BH/2, the Schwarzschild horizon")
      .default_value(0.0)
      .at_least(0);
  b.real("search_radius")
      .doc("half-width of the box about the puncture whose fields the search samples (hatted); 0: twice the starting "
           "radius; the surface must stay inside it")
      .default_value(0.0)
      .at_least(0);
  b.boolean("every_iteration")
      .doc("also find the horizon after every outer iteration's solve (progress shows bh_irreducible_mass)")
      .default_value(false);

  b.schedule(Bin::setup, "publish", [state](Context& ctx) {
     state->service->track = ctx.params().boolean("every_iteration");
     ctx.publish<ApparentHorizon>("horizon", state->service);
   }).doc("publish the horizon service (M_irr of the last search)");

  b.schedule(Bin::update, "track", [state](Context& ctx) {
     if (!ctx.params().boolean("every_iteration")) return;
     state->last = locate(ctx, *state);
     ctx.show_progress("bh_irreducible_mass", state->sigma * std::sqrt(state->last->area_hat / (16 * std::numbers::pi)));
   })
      .before_if_present("puncture.binary_update")
      .doc("with every_iteration: the horizon of the last solve, before the hole is moved");

  b.schedule(Bin::analysis, "find", [state](Context& ctx) {
     try {
       state->last = locate(ctx, *state);
     } catch (...) {
       state->last.reset();  // no surface of earlier fields in horizon.tsv
       throw;
     }
     report(ctx, *state);
     const Horizon& h = *state->last;
     ctx.log().info("horizon: M_irr = {:.9g}, area {:.9g}, coordinate radius {:.6g} .. {:.6g} (mean {:.6g}), spin {:.3e}; "
                    "{} Newton steps, max |phi^2 Theta| r = {:.2e}",
                    state->sigma * std::sqrt(h.area_hat / (16 * std::numbers::pi)), state->sigma * state->sigma * h.area_hat,
                    state->sigma * h.radius_min, state->sigma * h.radius_max, state->sigma * h.radius_mean,
                    state->sigma * state->sigma * h.spin_hat, h.iterations, h.residual);
   }).doc("the apparent horizon of the final fields: bh_horizon_area, bh_irreducible_mass, bh_horizon_radius_min/_max/_mean, "
          "bh_horizon_spin, bh_horizon_residual, bh_horizon_iterations, bh_horizon_shift_x/_y (the l = 1 part of the shape; physical)");

  b.schedule(Bin::output, "surface", [state](Context& ctx) {
     if (state->last) ctx.write_output("horizon.tsv", surface_table(*state));
   }).doc("horizon.tsv: the surface in the planes z = 0 and y = 0 (physical), when one was found");
}

}  // namespace
}  // namespace bhnsid::horizon

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "horizon", "1.0",
                                     "the apparent horizon about the puncture: area, irreducible mass, radii, spin",
                                     &bhnsid::horizon::declare};
  return &info;
}
