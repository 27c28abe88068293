// Test plugin: a loop whose state lives in the plugin's memory alone (a fixed-point iteration
// x <- x/2 + target/2 and the history of its changes), so that a resumed run can only end where an
// uninterrupted one does if the checkpoint carried that state back. target is steerable: a warm
// start from a run of another target takes its x.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"

namespace {
using namespace bhnsid::core;

struct State {
  double x = 0;
  std::vector<double> changes;
};

void declare(PluginBuilder& b) {
  auto s = std::make_shared<State>();
  b.real("target").doc("the fixed point").default_value(3.0).steerable();
  b.real("wobble").doc("amplitude of the step's sin(step) term, which makes every step count matter").default_value(1e-3);
  b.real("tolerance").doc("converged when the last change is below this").default_value(1e-6).greater_than(0);
  // A lattice that the loop does not read: what a warm start from the next coarser run may refine.
  b.integer("points").doc("a point count, doubled per refinement").default_value(std::int64_t{8}).refines(Refinement::doubles);
  b.real("spacing").doc("a spacing, halved per refinement").default_value(0.5).refines(Refinement::halves);
  b.schedule(Bin::initial, "start", [s](Context&) { s->x = 0; });
  b.schedule(Bin::update, "step", [s](Context& ctx) {
    const double next = 0.5 * s->x + 0.5 * ctx.params().real("target") + ctx.params().real("wobble") * std::sin(static_cast<double>(s->changes.size()));
    s->changes.push_back(std::fabs(next - s->x));
    s->x = next;
    ctx.show_progress("x", s->x);
  });
  b.check("converged", [s](Context& ctx) {
    const bool done = s->changes.size() > 1 && s->changes.back() < ctx.params().real("tolerance");
    return Convergence{done, fmt::format("change {:.3e}", s->changes.empty() ? 0.0 : s->changes.back())};
  });
  b.schedule(Bin::analysis, "report", [s](Context& ctx) {
    ctx.set_scalar("x", s->x);
    ctx.set_scalar("steps", static_cast<double>(s->changes.size()));
  });
  b.checkpoint(
      [s](Context&, CheckpointWriter& out) {
        out.put("x", s->x);
        out.put("changes", s->changes);
      },
      [s](Context&, const CheckpointReader& in) {
        s->x = in.real("x");
        s->changes = in.reals("changes");
      });
  // A neighbour's fixed point is this one's start; its history of changes is not this run's.
  b.warm_start([s](Context&, const CheckpointReader& in) { s->x = in.real("x"); });
}
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_checkpoint", "1.0", "test: loop state kept in a checkpoint",
                                     &declare};
  return &info;
}
