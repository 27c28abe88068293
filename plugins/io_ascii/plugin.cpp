// The io_ascii plugin (OUTPUT): every published FieldExport (the Einstein Toolkit's fields, physical
// units) along the x axis (y = z = 0) as one TSV table, axis_x.tsv, for a quick look or a plot
// without HDF5. Like io_hdf5 it knows no physics: it writes what the plugins publish.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <vector>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::io_ascii {
namespace {

using core::Bin;
using core::Context;

std::string axis_table(const Grid& grid, const std::vector<FieldExport*>& exports, double sigma) {
  const Level& lv = grid.finest();
  // The x axis: the middle row in y, and z = 0 (k = 0 under equatorial symmetry, the middle otherwise).
  const int j = lv.ny / 2, k = lv.z_symmetry ? 0 : lv.nz / 2;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  std::vector<double> buffer(lv.size);
  for (FieldExport* e : exports) {
    const std::vector<ExportField> fields = e->export_fields();
    for (std::size_t f = 0; f < fields.size(); ++f) {
      if (!fields[f].same_as.empty()) continue;  // equal to a column already there
      std::fill(buffer.begin(), buffer.end(), 0.0);
      e->fill(f, buffer.data());
      names.push_back(fields[f].group + "::" + fields[f].name);
      std::vector<double> column(static_cast<std::size_t>(lv.nx));
      for (int i = 0; i < lv.nx; ++i) column[static_cast<std::size_t>(i)] = buffer[lv.at(i, j, k)];
      columns.push_back(std::move(column));
    }
  }
  std::string out = fmt::format("# the published fields along the x axis (y = z = 0), physical units (x = sigma xhat, "
                                "sigma = {:.12g})\n# x", sigma);
  for (const std::string& n : names) out += "\t" + n;
  out += "\n";
  for (int i = 0; i < lv.nx; ++i) {
    out += fmt::format("{:.12g}", sigma * lv.x(i));
    for (const auto& c : columns) {
      const double v = c[static_cast<std::size_t>(i)];
      if (!std::isfinite(v))
        throw core::RunFailure(fmt::format("io_ascii: a published field is {} at x = {}; axis_x.tsv is not written", v,
                                           sigma * lv.x(i)));
      out += fmt::format("\t{:.15e}", v);
    }
    out += "\n";
  }
  return out;
}

void declare(core::PluginBuilder& b) {
  b.require("grid");
  b.schedule(Bin::output, "write", [](Context& ctx) {
     if (!ctx.run_record().initial_data) return;  // a signal before the initial data: no state
     const auto& grid = ctx.services().get<Grid>("grid");
     require_single_box(grid, ctx.plugin());
     const auto* fluid = ctx.services().find<Fluid>("star");
     ctx.write_output("axis_x.tsv", axis_table(grid, ctx.services().all<FieldExport>(), fluid ? fluid->sigma() : 1.0));
   }).doc("axis_x.tsv: every published field (ADMBase, HydroBase names) along the x axis, physical units; also after a "
          "failed loop");
}

}  // namespace
}  // namespace bhnsid::io_ascii

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "io_ascii", "0.1",
                                     "the published fields along the x axis as TSV (axis_x.tsv)", &bhnsid::io_ascii::declare};
  return &info;
}
