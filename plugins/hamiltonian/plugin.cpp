// The hamiltonian plugin: the Hamiltonian constraint (eq. ham_hat) for chi, published as the
// EllipticEquation "equation.hamiltonian" that the multigrid solver relaxes with the others.
#include <algorithm>
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "hamiltonian.hpp"

namespace bhnsid::hamiltonian {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::shared_ptr<HamiltonianEquation> equation;
};

// gamma_ij = phi^4 delta_ij (conformal flatness) in the coordinates x = sigma xhat, where the
// components keep their values (the metric is dimensionless).
std::shared_ptr<FieldExport> metric_export(Grid& grid) {
  auto out = std::make_shared<FieldExportList>();
  Grid* g = &grid;
  const char* names[6] = {"gxx", "gxy", "gxz", "gyy", "gyz", "gzz"};
  for (int c = 0; c < 6; ++c) {
    const bool diagonal = c == 0 || c == 3 || c == 5;
    const Parity parity{c == 2 || c == 4 ? -1 : 1, 1};
    out->add({"ADMBase", names[c], "1", parity,
              diagonal ? "phi^4, phi = Mhat_BH/(2 rhat_BH) + chi (eq. ham_hat)" : "0 (conformally flat)",
              c == 3 || c == 5 ? "gxx" : ""},
             [g, diagonal](double* gij) {
               const double* chi = g->data(g->field_id(fields::chi), 0, 0);
               const double* pphi = g->data(g->field_id(fields::puncture_phi), 0, 0);
               for_stored_points(g->finest(), [&](std::ptrdiff_t p) {
                 const double phi2 = (pphi[p] + chi[p]) * (pphi[p] + chi[p]);
                 gij[p] = diagonal ? phi2 * phi2 : 0.0;
               });
             });
  }
  return out;
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("grid");
  b.require("elliptic_solver");
  b.implements("equation.hamiltonian");
  b.implements("export.hamiltonian");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    m.count(memory_unknown_components, 1);
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability)) {
      layout->estimate_field(m, ctx.plugin(), fields::chi, 1);
      layout->estimate_field(m, ctx.plugin(), fields::puncture_phi, 1);
      layout->estimate_field(m, ctx.plugin(), fields::aa, 1);
    }
  });

  b.real("initial_chi").doc("starting value of chi everywhere (the star may overwrite it with its own guess)").default_value(1.0).greater_than(0);
  b.real("test_matter_scale")
      .doc("TEST ONLY: multiplies the matter term 2 pi sigma^2 phi^5 rho_E by this factor, so that tests can "
           "show that a one-coefficient error is detected; 1 for physics")
      .default_value(1.0);

  b.schedule(Bin::setup, "setup", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     require_single_box(grid, ctx.plugin());
     const auto* fluid = ctx.services().find<Fluid>("star");
     const auto* puncture = ctx.services().find<Puncture>("puncture");
     state->equation = std::make_shared<HamiltonianEquation>(grid, fluid, puncture, ctx.params().real("test_matter_scale"));
     ctx.publish<EllipticEquation>("equation.hamiltonian", state->equation);
     ctx.publish<FieldExport>("export.hamiltonian", metric_export(grid));
     ctx.log().info("Hamiltonian constraint for chi: {}, {}", fluid ? "with matter" : "vacuum",
                    puncture ? "with a puncture" : "no black hole");
   }).doc("register chi, puncture_phi, aa_hat, publish the equation and the export of gxx ... gzz");

  b.schedule(Bin::initial, "initial_data", [](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     double* chi = grid.data(grid.field_id(fields::chi), 0, 0);
     std::fill(chi, chi + grid.finest().size, ctx.params().real("initial_chi"));
   }).doc("chi = initial_chi on the finest level");

  b.schedule(Bin::solve, "puncture_term", [state](Context&) { state->equation->update_puncture(); })
      .before("elliptic_solver.solve")
      .doc("puncture_phi = Mhat_BH/(2 rhat_BH) on every level from the current puncture");
  // The redone UPDATE reads phi = puncture_phi + chi: it must be that of the puncture put back.
  b.schedule(Bin::retreat, "puncture_term_back", [state](Context&) { state->equation->update_puncture(); })
      .after_if_present("puncture.undo_update")
      .doc("puncture_phi again, from the puncture as RETREAT put it back");
}

}  // namespace
}  // namespace bhnsid::hamiltonian

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "hamiltonian", "1.0",
                                     "Hamiltonian constraint for chi (eq. ham_hat), an equation.* service",
                                     &bhnsid::hamiltonian::declare};
  return &info;
}
