// Test plugin: writes blob.bin in OUTPUT the way io_hdf5 writes data.h5 — by the path that
// Context::begin_output returns, opened with truncation as a library that opens by name does — so
// that a test can leave a symbolic link at blob.bin.partial and see that nothing is written through it.
#include <cstdio>
#include <stdexcept>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"

namespace {
using namespace bhnsid::core;

void declare(PluginBuilder& b) {
  b.schedule(Bin::output, "blob", [](Context& ctx) {
    const auto partial = ctx.begin_output("blob.bin");
    std::FILE* f = std::fopen(partial.c_str(), "w");
    if (!f) throw std::runtime_error("cannot open blob.bin.partial");
    std::fputs("blob of the run\n", f);
    std::fclose(f);
    ctx.commit_output("blob.bin");
  });
}
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_output", "1.0", "test: a file written by path in OUTPUT",
                                     &declare};
  return &info;
}
