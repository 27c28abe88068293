// Test plugin: requires a capability that no plugin implements.
#include "bhnsid/core/plugin.hpp"

namespace {
void declare(bhnsid::core::PluginBuilder& b) { b.require("nobody_has_this"); }
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_needs_missing", "1.0", "test: unmet requirement", &declare};
  return &info;
}
