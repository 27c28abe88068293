// Test plugin: declares a parameter without a doc and with a default outside its range.
#include "bhnsid/core/plugin.hpp"

namespace {
void declare(bhnsid::core::PluginBuilder& b) { b.real("undocumented").default_value(-1.0).at_least(0); }
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_bad_decl", "1.0", "test: bad declaration", &declare};
  return &info;
}
