// Test plugin: a FieldExport "nan_field" that is 1 everywhere but NaN at one point of the finest
// level, so that io_hdf5's refusal to write non-finite data can be seen.
#include <cmath>
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "bhnsid/interfaces/grid.hpp"

namespace {
using namespace bhnsid;
using namespace bhnsid::core;

void declare(PluginBuilder& b) {
  b.require("grid");
  b.implements("export.tp_nan_export");
  b.schedule(Bin::setup, "publish", [](Context& ctx) {
    auto out = std::make_shared<FieldExportList>();
    const Grid* g = &ctx.services().get<Grid>("grid");
    out->add({"TestBase", "nan_field", "1", Parity{}, "1, NaN at stored point (1, 2, 3)"}, [g](double* v) {
      for_stored_points(g->finest(), [&](std::ptrdiff_t p) { v[p] = 1.0; });
      v[g->finest().at(1, 2, 3)] = std::nan("");
    });
    ctx.publish<FieldExport>("export.tp_nan_export", out);
  });
}
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_nan_export", "1.0", "test: a field export with a NaN",
                                     &declare};
  return &info;
}
