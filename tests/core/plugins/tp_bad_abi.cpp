// Test plugin: built against a different (future) ABI version.
#include "bhnsid/core/plugin.hpp"

namespace {
void declare(bhnsid::core::PluginBuilder&) {}
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{999u, "tp_bad_abi", "1.0", "test: wrong ABI", &declare};
  return &info;
}
