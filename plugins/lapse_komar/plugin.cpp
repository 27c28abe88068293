// The lapse_komar plugin (implements "lapse"): maximal slicing with the singular puncture term
// eta = eta~ - c Mhat_BH/(2 rhat_BH), so that a lone hole has the static Schwarzschild lapse and a
// star beside the hole feels its full Newtonian pull (docs/lapse.md). c = 1 (static) or c from the
// virial condition M_Komar = M_ADM, updated every outer iteration (virial.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "komar.hpp"
#include "virial.hpp"

namespace bhnsid::lapse_komar {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::shared_ptr<Strength> strength = std::make_shared<Strength>();
  VirialSecant secant;
  VirialMeasure last;
  double before_update = 1;  ///< c before the last UPDATE, for RETREAT
  double step_fraction = 1;  ///< halved by each retreat, back to 1 after a step that stands
  bool converged = false;
};

std::array<double, 3> centre_of(const Context& ctx) {
  return falloff_centre(ctx.services().find<Fluid>("star"), ctx.services().find<Puncture>("puncture"));
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("grid");
  b.require("elliptic_solver");
  b.require("equation.hamiltonian");
  b.require("puncture");
  b.implements("lapse");
  b.implements("equation.lapse");
  b.implements("export.lapse");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    m.count(memory_unknown_components, 1);
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability)) {
      layout->estimate_field(m, ctx.plugin(), eta_regular, 1);
      layout->estimate_field(m, ctx.plugin(), fields::alpha, 1);
    }
  });

  b.keyword("condition", {"virial", "static"})
      .doc("the strength c of the singular term -c Mhat_BH/(2 rhat_BH) of alpha phi: virial = c such that the Komar "
           "mass equals the ADM mass (the quasi-equilibrium condition), updated every outer iteration; static = 1 "
           "(a lone hole gets the static Schwarzschild lapse)")
      .default_value(std::string("virial"));
  b.real("virial_tolerance")
      .doc("the loop goes on until the virial update would move c by at most this (dimensionless)")
      .default_value(1e-6)
      .greater_than(0)
      .at_most(0.1);
  b.real("initial_eta_regular")
      .doc("starting value of the regular part eta~ everywhere (the star may overwrite it)")
      .default_value(1.0)
      .greater_than(0);

  b.schedule(Bin::setup, "setup", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     require_single_box(grid, ctx.plugin());
     const auto* fluid = ctx.services().find<Fluid>("star");
     const auto& puncture = ctx.services().get<Puncture>("puncture");
     ctx.publish<EllipticEquation>("equation.lapse", std::make_shared<KomarEquation>(grid, fluid, puncture, state->strength));
     auto lapse = std::make_shared<KomarLapse>(state->strength);
     ctx.publish<Lapse>("lapse", lapse);
     auto out = std::make_shared<FieldExportList>();
     Grid* g = &grid;
     out->add({"ADMBase", "alp", "1", Parity{},
               "the lapse alpha = (eta~ - c Mhat_BH/(2 rhat_BH)) / phi: -c at the puncture, negative inside the horizon"},
              [g, lapse](double* alp) {
                const double* alpha = lapse_on(*g, *lapse, 0);
                for_stored_points(g->finest(), [&](std::ptrdiff_t p) { alp[p] = alpha[p]; });
              });
     ctx.publish<FieldExport>("export.lapse", out);
     ctx.log().info("lapse_komar: maximal slicing with the singular puncture term, c {}",
                    ctx.params().string("condition") == "static" ? "= 1 (static)" : "from the virial condition");
   })
      .after("equation.hamiltonian.setup")
      .doc("register eta_regular and alpha; publish the equation, the lapse and the export of alp");

  b.schedule(Bin::initial, "initial_data", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     double* eta = grid.data(grid.field_id(eta_regular), 0, 0);
     std::fill(eta, eta + grid.finest().size, ctx.params().real("initial_eta_regular"));
     state->strength->c = 1;
     state->secant.forget();
     state->converged = false;
   }).doc("eta~ = initial_eta_regular on the finest level, c = 1");

  b.schedule(Bin::update, "virial", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     const auto& puncture = ctx.services().get<Puncture>("puncture");
     double& c = state->strength->c;
     state->last = measure_virial(grid, c, puncture, centre_of(ctx));
     state->before_update = c;
     if (ctx.params().string("condition") == "static") {
       state->converged = true;
       return;
     }
     const double next = state->secant.next(c, state->last, puncture.bare_mass(), state->step_fraction);
     if (!std::isfinite(next))
       throw core::RunFailure(fmt::format(
           "lapse_komar: no virial update of c: the 1/r coefficients of eta and phi are {} and {}; they are fitted over "
           "the cube surfaces between half the box and its faces that enclose the star and the hole, and fewer than four "
           "do (enlarge grid.n or grid.dx, or set lapse_komar.condition: static)",
           state->last.b_eta, state->last.b_phi));
     state->converged = std::fabs(next - c) <= ctx.params().real("virial_tolerance");
     // A converged step keeps the c the fields were solved with, so that the output is consistent.
     if (!state->converged) c = next;
     state->step_fraction = 1;
     ctx.show_progress("lapse_komar_c", c);
     ctx.log().detail("lapse_komar: M_Komar/M_ADM = {:.9f} (B_eta = {:.9g}, B_phi = {:.9g}), c -> {:.12g}",
                      state->last.ratio(), state->last.b_eta, state->last.b_phi, c);
   })
      .before_if_present("puncture.binary_update")
      .doc("measure M_Komar/M_ADM from the 1/r coefficients of eta and phi; with condition = virial a secant step on c");

  b.check("virial_converged", [state](Context& ctx) {
     return core::Convergence{state->converged,
                              fmt::format("M_Komar/M_ADM = {:.9f}, c = {:.12g} ({})", state->last.ratio(),
                                          state->strength->c, ctx.params().string("condition"))};
   }).doc("with condition = virial, the last update moved c by at most virial_tolerance");

  b.schedule(Bin::retreat, "undo_virial", [state](Context&) {
     state->strength->c = state->before_update;
     state->secant.forget();
     state->step_fraction *= 0.5;
   }).doc("c back to before its last update; the next update takes half the step");

  const auto restore = [state](Context&, const core::CheckpointReader& in) {
    const std::vector<double> v = in.reals("strength");
    if (v.size() != 1 || !std::isfinite(v[0])) throw core::InputError("lapse_komar: the checkpoint's strength is malformed");
    state->strength->c = v[0];
    state->before_update = v[0];
    state->secant.forget();
  };
  b.checkpoint([state](Context&, core::CheckpointWriter& out) { out.put("strength", std::vector<double>{state->strength->c}); },
               restore);
  b.warm_start(restore);

  b.schedule(Bin::analysis, "report", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     const auto& puncture = ctx.services().get<Puncture>("puncture");
     const VirialMeasure m = measure_virial(grid, state->strength->c, puncture, centre_of(ctx));
     ctx.set_scalar("lapse_komar_c", state->strength->c);
     ctx.set_scalar("lapse_komar_virial_ratio", m.ratio());
   }).doc("lapse_komar_c and lapse_komar_virial_ratio (M_Komar/M_ADM from the 1/r coefficients of eta and phi)");
}

}  // namespace
}  // namespace bhnsid::lapse_komar

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "lapse_komar", "1.0",
                                     "maximal slicing with the singular puncture term (static or virial), the lapse",
                                     &bhnsid::lapse_komar::declare};
  return &info;
}
