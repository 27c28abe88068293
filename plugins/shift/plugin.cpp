// The shift plugin: the minimal-distortion shift (eq. mindist_hat) for beta^i, published as the
// EllipticEquation "equation.shift" that the multigrid relaxes with the other field equations, with
// the excision cube about the puncture (physics-notes §2.5, §4.6).
#include <memory>
#include <string>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "shift.hpp"

namespace bhnsid::shift {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::shared_ptr<ShiftEquation> equation;
};

void log_excision(const Context& ctx, const ExcisionReport& r) {
  std::string coarse;
  for (int l : r.nearest_levels) coarse += (coarse.empty() ? "" : ", ") + std::to_string(l);
  // Once per outer iteration inside the loop: the log's detail, not the terminal's.
  const std::string line = fmt::format("shift: excision cube of side {:.6g} about ({:.6g}, {:.6g}, {:.6g}), held [{:.6g}, {:.6g}] x [{:.6g}, "
                 "{:.6g}] x [{:.6g}, {:.6g}], {} finest-level points{}; beta_0 = ({:.9g}, {:.9g}, {:.9g})",
                 r.cube.side, r.cube.centre[0], r.cube.centre[1], r.cube.centre[2], r.cube.lo[0], r.cube.hi[0],
                 r.cube.lo[1], r.cube.hi[1], r.cube.lo[2], r.cube.hi[2], r.finest_points,
                 coarse.empty() ? std::string{} : "; nearest point held on level(s) " + coarse, r.beta0[0], r.beta0[1],
                 r.beta0[2]);
  if (ctx.iteration() > 0)
    ctx.log().detail(line);
  else
    ctx.log().info(line);
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("grid");
  b.require("elliptic_solver");
  b.require("lapse");
  b.implements("equation.shift");
  b.implements("export.shift");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    m.count(memory_unknown_components, 3);
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability)) {
      layout->estimate_field(m, ctx.plugin(), fields::shift, 3);
    }
  });

  b.keyword("excision_value", {"lorentz", "plain"})
      .doc("shift held in the excision cube (dimensionless): lorentz = -v/sqrt(1 - |v|^2) (the paper's beta_0), "
           "plain = -v, with v = Phat_BH/Mhat_BH")
      .default_value(std::string("lorentz"));
  b.real("excision_min_side")
      .doc("smallest full side of the excision cube (hatted length); the side is max(Mhat_BH/2, 3 dx, this). A "
           "fixed side lets runs at several dx excise the same region (convergence studies); 0 for the paper's rule")
      .default_value(0.0)
      .at_least(0);
  b.real("excision_lattice")
      .doc("hatted length D = dx 2^p (p >= 0): each face of the excision cube moves to the nearest plane of the "
           "lattice of spacing D through the grid's corner, so that runs at dx, dx/2, dx/4 with the same D and r_c "
           "excise exactly the same region (second-order convergence studies); 0: the cube exactly about the hole, "
           "a staircase that changes with dx (first-order errors next to it)")
      .default_value(0.0)
      .at_least(0);
  b.integer("local_sweeps")
      .doc("extra red-black sweeps on a box about the excision cube after every multigrid sweep of the shift (the "
           "coefficient 6 dphi/phi ~ 6/r and the coarse levels' larger cubes make the points within ~10 of the cube the "
           "slow ones); 0: off")
      .default_value(16)
      .at_least(0);
  b.integer("local_width")
      .doc("the box of the local sweeps: the held points' bounding box widened by this many points per side")
      .default_value(8)
      .at_least(0);
  b.integer("local_levels")
      .doc("the finest levels that get local_sweeps box sweeps; the coarser ones, where the box covers much of the "
           "level, get coarse_local_sweeps")
      .default_value(2)
      .at_least(0);
  b.integer("coarse_local_sweeps")
      .doc("box sweeps after every multigrid sweep of the shift on the levels below the finest local_levels")
      .default_value(4)
      .at_least(0);
  b.real("test_coupling_scale")
      .doc("TEST ONLY: multiplies the term (6/phi)[(d_j beta^i + d_i beta^j) dphi_j - (2/3) dphi_i div beta] "
           "(dimensionless), so that tests can show that the IRE (bhnsid validate) detects a one-coefficient error "
           "in vacuum, where the Ahat term is small; 1 for physics")
      .default_value(1.0);
  b.real("test_source_scale")
      .doc("TEST ONLY: multiplies the Ahat term 2 phi^-6 Ahat^ij d_j alpha (dimensionless), so that tests can show "
           "that a one-coefficient error is detected; 1 for physics")
      .default_value(1.0);

  b.schedule(Bin::setup, "setup", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     require_single_box(grid, ctx.plugin());
     const auto* fluid = ctx.services().find<Fluid>("star");
     const auto* puncture = ctx.services().find<Puncture>("puncture");
     Settings settings;
     settings.excision_value =
         ctx.params().string("excision_value") == "plain" ? ExcisionValue::plain : ExcisionValue::lorentz;
     settings.source_scale = ctx.params().real("test_source_scale");
     settings.coupling_scale = ctx.params().real("test_coupling_scale");
     settings.min_side = ctx.params().real("excision_min_side");
     settings.lattice = ctx.params().real("excision_lattice");
     settings.local_sweeps = static_cast<int>(ctx.params().integer("local_sweeps"));
     settings.local_width = static_cast<int>(ctx.params().integer("local_width"));
     settings.local_levels = static_cast<int>(ctx.params().integer("local_levels"));
     settings.coarse_local_sweeps = static_cast<int>(ctx.params().integer("coarse_local_sweeps"));
     state->equation = std::make_shared<ShiftEquation>(grid, ctx.services().find<Lapse>("lapse"), fluid, puncture, settings);
     ctx.publish<EllipticEquation>("equation.shift", state->equation);
     // beta^i = dx^i/dt keeps its values under x = sigma xhat, t = sigma that; inside the excision
     // cube it is the held beta_0 (finite, not a solution there).
     auto out = std::make_shared<FieldExportList>();
     Grid* g = &grid;
     const ShiftEquation* eq = state->equation.get();
     const auto held = [eq, fluid]() -> std::optional<ExcisionRegion> {
       const std::optional<Cube> cube = eq->held_cube();
       if (!cube) return std::nullopt;
       const double sigma = fluid ? fluid->sigma() : 1.0;
       return ExcisionRegion{ExcisionRegion::Shape::cube,
                             {sigma * cube->centre[0], sigma * cube->centre[1], sigma * cube->centre[2]},
                             sigma * cube->half};
     };
     const char* names[3] = {"betax", "betay", "betaz"};
     for (int c = 0; c < 3; ++c)
       out->add({"ADMBase", names[c], "1", Parity{c == 2 ? -1 : 1, 1},
                 "the shift beta^i (eq. mindist_hat); inside the excision cube the held value beta_0"},
                [g, c](double* beta) {
                  const double* b = g->data(g->field_id(fields::shift), c, 0);
                  for_stored_points(g->finest(), [&](std::ptrdiff_t p) { beta[p] = b[p]; });
                },
                held);
     ctx.publish<FieldExport>("export.shift", out);
     ctx.log().info("minimal-distortion shift: {}, {}", fluid ? "with matter" : "vacuum",
                    puncture ? "with an excised puncture" : "no black hole");
     if (puncture) log_excision(ctx, state->equation->update_puncture());
   })
      .after_if_present("equation.hamiltonian.setup")
      .after("lapse.setup")
      .after_if_present("equation.momentum.setup")
      .doc("check chi, alpha, ahat; register beta (and the excision mask); publish the equation and the export of betax, "
           "betay, betaz");

  b.checkpoint([state](Context&, core::CheckpointWriter& out) { state->equation->save(out); },
               [state](Context&, const core::CheckpointReader& in) { state->equation->restore(in); });
  // The excision state that goes with the masks the grid's warm start hands over (a run of the same
  // lattice; from a coarser one SETUP's excision stays, as the grid's masks do).
  b.warm_start([state](Context&, const core::CheckpointReader& in) { state->equation->warm_start(in); });

  b.schedule(Bin::solve, "excision", [state](Context& ctx) {
     const ExcisionReport r = state->equation->update_puncture();
     if (r.cube.side == 0) return;  // no puncture
     if (r.changed) log_excision(ctx, r);
     if (r.coarsest_changed)
       ctx.log().warn("shift: the held points of the coarsest level changed with the puncture; the multigrid indexes "
                      "the coarsest level's unknowns once (plugins/multigrid coarse_solver), so its direct solve may "
                      "now fail as singular");
     ctx.set_scalar("shift_excision_side", r.cube.side);
     ctx.set_scalar("shift_excision_points", r.finest_points);
   })
      .before("elliptic_solver.solve")
      .doc("the excision mask on every level when the puncture moved; beta = beta_0 on "
           "every excised point");
}

}  // namespace
}  // namespace bhnsid::shift

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "shift", "1.0",
                                     "minimal-distortion shift beta^i (eq. mindist_hat) with the excision cube, an "
                                     "equation.* service",
                                     &bhnsid::shift::declare};
  return &info;
}
