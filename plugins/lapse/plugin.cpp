// The lapse plugin: maximal slicing (eq. maxslice_hat) for eta = alpha phi, published as the
// EllipticEquation "equation.lapse", relaxed together with the Hamiltonian constraint.
#include <algorithm>
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "lapse.hpp"

namespace bhnsid::lapse {
namespace {

using core::Bin;
using core::Context;

void declare(core::PluginBuilder& b) {
  b.require("grid");
  b.require("elliptic_solver");
  b.require("equation.hamiltonian");
  b.implements("lapse");
  b.implements("equation.lapse");
  b.implements("export.lapse");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    m.count(memory_unknown_components, 1);
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability)) {
      layout->estimate_field(m, ctx.plugin(), fields::eta, 1);
      layout->estimate_field(m, ctx.plugin(), fields::alpha, 1);
    }
  });

  b.real("initial_eta").doc("starting value of eta = alpha phi everywhere (the star may overwrite it)").default_value(1.0).greater_than(0);
  b.real("test_matter_scale")
      .doc("TEST ONLY: multiplies the matter term 2 pi sigma^2 phi^4 (rho_E + 2S) by this factor, so that tests "
           "can show that a one-coefficient error is detected; 1 for physics")
      .default_value(1.0);

  b.schedule(Bin::setup, "setup", [](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     require_single_box(grid, ctx.plugin());
     const auto* fluid = ctx.services().find<Fluid>("star");
     const auto* puncture = ctx.services().find<Puncture>("puncture");
     ctx.publish<EllipticEquation>("equation.lapse",
                                   std::make_shared<LapseEquation>(grid, fluid, puncture, ctx.params().real("test_matter_scale")));
     auto lapse = std::make_shared<EtaLapse>();
     ctx.publish<Lapse>("lapse", lapse);
     auto out = std::make_shared<FieldExportList>();
     Grid* g = &grid;
     out->add({"ADMBase", "alp", "1", Parity{}, "the lapse alpha = eta / phi, phi = Mhat_BH/(2 rhat_BH) + chi"},
              [g, lapse](double* alp) {
                const double* alpha = lapse_on(*g, *lapse, 0);
                for_stored_points(g->finest(), [&](std::ptrdiff_t p) { alp[p] = alpha[p]; });
              });
     ctx.publish<FieldExport>("export.lapse", out);
   })
      .after("equation.hamiltonian.setup")
      .doc("register eta and alpha, publish the equation, the lapse and the export of alp");

  b.schedule(Bin::initial, "initial_data", [](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     double* eta = grid.data(grid.field_id(fields::eta), 0, 0);
     std::fill(eta, eta + grid.finest().size, ctx.params().real("initial_eta"));
   }).doc("eta = initial_eta on the finest level");
}

}  // namespace
}  // namespace bhnsid::lapse

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "lapse", "1.0",
                                     "maximal slicing for eta = alpha phi (eq. maxslice_hat), an equation.* service",
                                     &bhnsid::lapse::declare};
  return &info;
}
