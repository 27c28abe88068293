// The momentum plugin: the momentum constraint for the vector potential W^i (eq. mom_ansatz_hat),
// published as the EllipticEquation "equation.momentum" that the multigrid solver relaxes with the
// others, and the owner of Ahat^ij = Ahat_BY^ij + Zhat^ij and aa_hat on every level.
#include <fmt/format.h>

#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "momentum.hpp"

namespace bhnsid::momentum {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::shared_ptr<MomentumEquation> equation;
  CurvatureChange last;  ///< of the fill after the last solve
};

// K_ij = phi^-2 A_ij (A_ij = phi^2 K_ij, physics-notes §1.2), A = Ahat / sigma in the coordinates
// x = sigma xhat (§1.3): Bowen-York and Zhat together, as the last solve left them.
std::shared_ptr<FieldExport> curvature_export(Grid& grid, const Fluid* fluid) {
  auto out = std::make_shared<FieldExportList>();
  Grid* g = &grid;
  const char* names[6] = {"kxx", "kxy", "kxz", "kyy", "kyz", "kzz"};
  for (int c = 0; c < 6; ++c)
    out->add({"ADMBase", names[c], "1/length", Parity{c == 2 || c == 4 ? -1 : 1, 1},
              "the extrinsic curvature K_ij = phi^-2 (Ahat_BY + Zhat)_ij / sigma (K = 0, maximal slicing)"},
             [g, fluid, c](double* k) {
               const double inv_sigma = fluid ? 1.0 / fluid->sigma() : 1.0;
               const double* a = g->data(g->field_id(fields::ahat), c, 0);
               const double* chi = g->data(g->field_id(fields::chi), 0, 0);
               const double* pphi = g->data(g->field_id(fields::puncture_phi), 0, 0);
               for_stored_points(g->finest(), [&](std::ptrdiff_t p) {
                 const double phi = pphi[p] + chi[p];
                 k[p] = a[p] * inv_sigma / (phi * phi);
               });
             });
  return out;
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("grid");
  b.require("elliptic_solver");
  b.implements("equation.momentum");
  b.implements("export.momentum");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    m.count(memory_unknown_components, 3);
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability)) {
      layout->estimate_field(m, ctx.plugin(), fields::wvec, 3);
      layout->estimate_field(m, ctx.plugin(), fields::ahat, 6);
      layout->estimate_field(m, ctx.plugin(), fields::ansatz_weight, 1);
    }
  });

  b.keyword("weight", {"lapse", "unit"})
      .doc("the positive weight q of the vector-potential ansatz Zhat = chi^7/(2 q) (LW): lapse = the lapse's regular "
           "part (the paper's eta = alpha phi; eta~ under lapse_komar), unit = 1; any positive q solves the momentum "
           "constraint exactly, the choice moves the data by what the ansatz leaves free")
      .default_value(std::string("lapse"));
  b.real("test_source_scale")
      .doc("TEST ONLY: multiplies the matter term 16 pi sigma^2 q phi^10 chi^-7 J^i by this factor, so that "
           "tests can show that a one-coefficient error is detected; 1 for physics")
      .default_value(1.0);
  b.real("curvature_tolerance")
      .doc("the loop goes on until the Ahat that the equations were solved with (filled before the solve) and the "
           "Ahat of the solved W differ by at most this times max |Zhat| (or by 1e-13) on the finest level")
      .default_value(1e-5)
      .greater_than(0);

  b.schedule(Bin::setup, "setup", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     require_single_box(grid, ctx.plugin());
     const auto* fluid = ctx.services().find<Fluid>("star");
     const auto* puncture = ctx.services().find<Puncture>("puncture");
     const Weight weight = ctx.params().string("weight") == "unit" ? Weight::unit : Weight::lapse;
     state->equation = std::make_shared<MomentumEquation>(grid, ctx.services().find<Lapse>("lapse"), weight, fluid,
                                                          puncture, ctx.params().real("test_source_scale"));
     ctx.publish<EllipticEquation>("equation.momentum", state->equation);
     ctx.publish<FieldExport>("export.momentum", curvature_export(grid, fluid));
     ctx.log().info("momentum constraint for W^i: {}, {}", fluid ? "with matter" : "vacuum",
                    puncture ? "with a Bowen-York puncture" : "no black hole");
   })
      .after_if_present("equation.hamiltonian.setup")
      .after_if_present("lapse.setup")
      .doc("check that chi, puncture_phi (and the lapse's regular part) exist; register wvec, wvec_weight, ahat, aa_hat; publish the equation and the export of "
           "kxx ... kzz");

  b.schedule(Bin::solve, "curvature", [state](Context&) { state->equation->fill_curvature(); })
      .before("elliptic_solver.solve")
      .doc("ahat = Bowen-York + Zhat and aa_hat on every level, for the equations solved next");

  b.schedule(Bin::solve, "curvature_after_solve", [state](Context& ctx) {
     state->last = state->equation->fill_curvature();
     ctx.set_scalar("momentum_ahat_change", state->last.max_change);
     ctx.set_scalar("momentum_zhat_max", state->last.max_zhat);
   })
      .after("elliptic_solver.solve")
      .doc("ahat and aa_hat again from the solved W, chi, q, so that the output is consistent");

  b.check("curvature_consistent", [state](Context& ctx) {
     const double tol = ctx.params().real("curvature_tolerance");
     const CurvatureChange& c = state->last;
     // The absolute floor covers W = 0 up to rounding (vacuum), where max |Zhat| is no scale.
     return core::Convergence{c.max_change <= tol * c.max_zhat || c.max_change <= 1e-13,
                              fmt::format("Ahat moved by {:.3e} in the solve (max |Zhat| {:.3e}, tol {:.1e} relative)",
                                          c.max_change, c.max_zhat, tol)};
   }).doc("the equations saw the Ahat of the solved W: Ahat changed by at most curvature_tolerance max |Zhat| in the last solve");
}

}  // namespace
}  // namespace bhnsid::momentum

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "momentum", "1.0",
                                     "momentum constraint for the vector potential W^i (eq. mom_ansatz_hat) and Ahat^ij, "
                                     "an equation.* service",
                                     &bhnsid::momentum::declare};
  return &info;
}
