// Test plugin: implements `counter` too, so it conflicts with tp_counter.
#include "bhnsid/core/plugin.hpp"

namespace {
void declare(bhnsid::core::PluginBuilder& b) { b.implements("counter"); }
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_twin", "1.0", "test: second counter", &declare};
  return &info;
}
