// Test plugin: orders itself after an entry that the active tp_counter does not have.
#include "bhnsid/core/plugin.hpp"

namespace {
using namespace bhnsid::core;
void declare(PluginBuilder& b) { b.schedule(Bin::setup, "late", [](Context&) {}).after("counter.no_such_entry"); }
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_bad_ref", "1.0", "test: dangling reference", &declare};
  return &info;
}
