// Test plugin: two SETUP entries that each insist on running before the other.
#include "bhnsid/core/plugin.hpp"

namespace {
using namespace bhnsid::core;
void declare(PluginBuilder& b) {
  b.implements("cycle");
  b.schedule(Bin::setup, "first", [](Context&) {}).before("cycle.second");
  b.schedule(Bin::setup, "second", [](Context&) {}).before("cycle.first");
}
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_cycle", "1.0", "test: cyclic schedule", &declare};
  return &info;
}
