// Test plugin: requires the `counter` capability, orders itself around tp_counter's entries
// (and, if present, around a capability that no active plugin implements), reads the service.
#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "tp_interfaces.hpp"

namespace {
using namespace bhnsid::core;

void declare(PluginBuilder& b) {
  b.require("counter");
  b.schedule(Bin::initial, "before_counter", [](Context& ctx) {
    ctx.set_scalar("partner_saw_counter", ctx.services().get<bhnsid::test::CounterService>("counter").value);
  }).before("counter.initial").after_if_present("not_loaded.anything").doc("runs before tp_counter.initial");
  b.schedule(Bin::analysis, "after_counter", [](Context& ctx) {
    ctx.set_scalar("partner_final_counter", ctx.services().get<bhnsid::test::CounterService>("counter").value);
  }).after("counter.analysis");
}
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_partner", "1.0", "test: requires counter, ordered", &declare};
  return &info;
}
