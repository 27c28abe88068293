// Test plugin: dies by SIGKILL at a chosen point of a run, when the environment asks
// (BHNSID_TEST_KILL = "solve:K": at the start of iteration K's SOLVE, checkpoint K-1 on disk;
// "save:K": inside its own checkpoint section of iteration K, after 4 MiB of it were written, so
// the checkpoint is left a truncated .partial; "analysis": in ANALYSIS, after the loop's last
// checkpoint; "sigint_in_restore": SIGINT to itself while its checkpoint section is restored, a
// stop request arriving during a resume's restore). Without the variable it does nothing, so a run
// with it computes exactly what a run without it does, and its parameters match on --resume.
#include <csignal>
#include <cstdlib>
#include <string>
#include <vector>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"

namespace {
using namespace bhnsid::core;

bool asked(const char* where, int iteration) {
  const char* env = std::getenv("BHNSID_TEST_KILL");
  return env && std::string(env) == std::string(where) + ":" + std::to_string(iteration);
}

void declare(PluginBuilder& b) {
  b.schedule(Bin::solve, "kill", [](Context& ctx) {
     if (asked("solve", ctx.iteration())) std::raise(SIGKILL);
   }).doc("SIGKILL at the start of SOLVE of the iteration BHNSID_TEST_KILL=solve:K names");
  b.schedule(Bin::analysis, "kill_in_analysis", [](Context&) {
     const char* env = std::getenv("BHNSID_TEST_KILL");
     if (env && std::string(env) == "analysis") std::raise(SIGKILL);
   }).doc("SIGKILL in ANALYSIS when BHNSID_TEST_KILL=analysis");
  b.checkpoint(
      [](Context& ctx, CheckpointWriter& out) {
        const std::vector<double> padding(1 << 19, 1.0);
        out.put("padding", padding);
        if (asked("save", ctx.iteration())) std::raise(SIGKILL);
      },
      [](Context&, const CheckpointReader& in) {
        (void)in.reals("padding");
        const char* env = std::getenv("BHNSID_TEST_KILL");
        if (env && std::string(env) == "sigint_in_restore") std::raise(SIGINT);
      });
}
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_kill", "1.0", "test: SIGKILL at a chosen point of the loop",
                                     &declare};
  return &info;
}
