// Test plugin: its SOLVE entry (after any elliptic solver's) fails with a StepFailure at chosen
// iterations, a chosen number of attempts in a row, so that the core's retreat can be watched: it
// records every UPDATE with its step fraction and every RETREAT into steps.txt (OUTPUT).
#include <fmt/format.h>

#include <memory>
#include <string>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"

namespace {
using namespace bhnsid::core;

struct State {
  std::string steps;
  int failed_at = 0;  ///< the iteration of the current run of failures
  int failures = 0;   ///< failed attempts at that iteration
  bool fail_once(Context& ctx) {
    const auto at = ctx.params().integer("fail_at");
    if (at == 0 || ctx.iteration() != at) return false;
    if (failed_at != at) failed_at = static_cast<int>(at), failures = 0;
    if (failures >= ctx.params().integer("failures")) return false;
    ++failures;
    return true;
  }
};

void declare(PluginBuilder& b) {
  auto s = std::make_shared<State>();
  b.integer("fail_at").doc("the iteration whose SOLVE fails; 0 never").default_value(std::int64_t{0}).at_least(0);
  b.integer("failures").doc("attempts in a row that fail at that iteration").default_value(std::int64_t{1}).at_least(0);
  b.boolean("retreats").doc("register a RETREAT entry").default_value(true);
  b.integer("converge_after").doc("iterations until CHECK converges; 0: it always agrees").default_value(std::int64_t{4}).at_least(0);
  b.schedule(Bin::solve, "solve", [s](Context& ctx) {
     if (s->fail_once(ctx))
       throw StepFailure(fmt::format("deliberate step failure {} at iteration {}", s->failures, ctx.iteration()));
   })
      .after_if_present("elliptic_solver.solve")
      .doc("fails with a StepFailure at fail_at");
  b.schedule(Bin::update, "update", [s](Context& ctx) {
    s->steps += fmt::format("update {} {}\n", ctx.iteration(), ctx.step_fraction());
  });
  b.schedule(Bin::retreat, "retreat", [s](Context& ctx) {
    if (!ctx.params().boolean("retreats")) throw RunFailure("tp_step_failure: retreats are off");
    s->steps += fmt::format("retreat {}\n", ctx.iteration());
  });
  b.check("check", [](Context& ctx) {
    const auto after = ctx.params().integer("converge_after");
    return Convergence{after == 0 || ctx.iteration() >= after, ""};
  });
  b.schedule(Bin::output, "output", [s](Context& ctx) { ctx.write_output("steps.txt", s->steps); });
}
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_step_failure", "1.0", "test: SOLVE step failures and RETREAT",
                                     &declare};
  return &info;
}
