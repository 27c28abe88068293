// The flow_irrotational plugin (implements "flow"): the star's fluid without vorticity, its velocity
// from a potential solved with the star (irrotational.hpp, potential.hpp). Named in `plugins:` in
// place of flow_corotating; the star, the equations and the tools are the same.
#include <fmt/format.h>

#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "irrotational.hpp"

namespace bhnsid::flow_irrotational {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::shared_ptr<Irrotational> flow;
};

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("grid");
  b.require("eos");
  b.require("lapse");
  b.require("star");
  b.implements("flow");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability)) {
      layout->estimate_field(m, ctx.plugin(), potential_field, 1);
      // Finest-level arrays: the solve's copies of alpha, phi, beta and the level set, the face
      // coefficients (3), the unknowns' index map, the rotation's part of the potential, the last
      // reset's enthalpy and level set, the potential before the solve.
      m.add(ctx.plugin(), "scratch", fmt::format("fourteen finest-level scratch arrays at {}", layout->describe()),
            14 * layout->field_bytes(core::Storage::finest_only));
    }
  });
  b.real("tolerance")
      .doc("relative residual at which the velocity potential's linear solves stop (BiCGSTAB, GMRES where it breaks "
           "down, on the star's physical vertices)")
      .default_value(1e-10)
      .greater_than(0)
      .less_than(1e-2);
  b.integer("face_samples")
      .doc("sub-squares per side of a face the star's surface cuts, for the face average of rho0 (midpoint rule on "
           "the linear enthalpy level set; any EOS)")
      .default_value(std::int64_t{16})
      .at_least(1)
      .at_most(256);

  b.real("relaxation")
      .doc("fraction of each outer step's change of the velocity potential taken (1: the whole solve); 0.5 makes the "
           "SLy binary converge (it fails in its third step with 1) and takes the quick start at n = 64 from 30 outer "
           "steps to 25, but slows others (docs/irrotational.md)")
      .default_value(1.0)
      .greater_than(0)
      .at_most(1.0);
  b.integer("corotating_start")
      .doc("outer steps of a cold start (the potential 0 everywhere) taken with the corotating flow before the "
           "potential is first solved, so that the shift carries the orbit's momentum when it is (0: none; the "
           "mu_bn = 10 binary needs 1 or more; a warm start or a resumed run with a potential takes none)")
      .default_value(std::int64_t{0})
      .at_least(0)
      .at_most(1000);
  b.schedule(Bin::startup, "publish", [state](Context& ctx) {
     PotentialSettings s;
     s.tolerance = ctx.params().real("tolerance");
     s.face_samples = static_cast<int>(ctx.params().integer("face_samples"));
     s.relaxation = ctx.params().real("relaxation");
     state->flow = std::make_shared<Irrotational>(s, static_cast<int>(ctx.params().integer("corotating_start")));
     ctx.publish<Flow>("flow", state->flow);
   }).doc("publish the irrotational flow for the star");
  b.schedule(Bin::setup, "setup", [state](Context& ctx) {
     state->flow->attach(ctx.services().get<Grid>("grid"), ctx.services().get<Lapse>("lapse"),
                         ctx.services().get<Eos>("eos"));
   })
      .after("lapse.setup")
      .doc("register psi_tilde (the potential over sigma C_B, all levels), take the lapse and the EOS");
  b.schedule(Bin::update, "report_potential", [state](Context& ctx) {
     const PotentialSolve& s = state->flow->last_solve();
     ctx.log().detail("flow_irrotational: potential on {} vertices, {} iterations, relative residual {:.2e}", s.unknowns,
                      s.iterations, s.residual);
   })
      .after("star.outer_step")
      .doc("log the last potential solve");
  b.schedule(Bin::analysis, "report", [state](Context& ctx) {
     const PotentialSolve& s = state->flow->last_solve();
     ctx.set_scalar("potential_unknowns", s.unknowns);
     ctx.set_scalar("potential_iterations", s.iterations);
     ctx.set_scalar("potential_residual", s.residual);
     const auto size = state->flow->potential_size(ctx.services().get<Grid>("grid"));
     ctx.set_scalar("potential_max", size[0]);
     ctx.set_scalar("potential_gradient_max", size[1]);
     ctx.set_scalar("potential_rms", size[2]);
   }).doc("potential_unknowns, potential_iterations, potential_residual of the last solve; potential_max (max "
          "|Psitilde| in the star, gauge 0 at its centre), potential_gradient_max (max |dhat Psitilde|) and "
          "potential_rms (the rms of Psitilde weighted by rho0)");
}

}  // namespace
}  // namespace bhnsid::flow_irrotational

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "flow_irrotational", "0.1",
                                     "irrotational flow: h u = grad Psi, Psi from rest-mass conservation, first "
                                     "integral h alpha W - B.grad Psi = C_B",
                                     &bhnsid::flow_irrotational::declare};
  return &info;
}
