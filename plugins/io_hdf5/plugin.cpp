// The io_hdf5 plugin (OUTPUT): data.h5 with the Einstein Toolkit's fields that the physics plugins
// publish (FieldExport services), the solver's own fields, the scalars and the run's records, and
// data.xdmf beside it for ParaView and VisIt. The layout is docs/output-format.md.
#include <fmt/format.h>

#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "data_file.hpp"
#include "xdmf.hpp"

namespace bhnsid::io_hdf5 {
namespace {

using core::Bin;
using core::Context;

constexpr const char* data_name = "data.h5";
constexpr const char* xdmf_name = "data.xdmf";

void write(Context& ctx) {
  const auto& grid = ctx.services().get<Grid>("grid");
  require_single_box(grid, ctx.plugin());
  Settings settings;
  settings.compression = static_cast<int>(ctx.params().integer("compression"));
  const std::string& which = ctx.params().string("variables");
  settings.all_variables = which == "all";
  if (which == "unknowns")
    for (const EllipticEquation* e : ctx.services().all<EllipticEquation>()) settings.variables.push_back(e->unknown());
  const core::RunRecord record = ctx.run_record();
  // A signal before the initial data leaves no state: nothing to write (and fields still zero).
  if (!record.initial_data) {
    ctx.log().info("io_hdf5: no {}: the run stopped before its initial data", data_name);
    return;
  }
  EosRecord eos;
  eos.eos = ctx.services().find<Eos>("eos");
  for (const auto& [capability, plugin] : record.implementations)
    if (capability == "eos") eos.plugin = plugin;
  const auto* fluid = ctx.services().find<Fluid>("star");
  const double sigma = fluid ? fluid->sigma() : 1.0;
  std::vector<const FieldExport*> exports;
  for (const FieldExport* e : ctx.services().all<FieldExport>()) exports.push_back(e);

  const auto partial = ctx.begin_output(data_name);
  DataFile file;
  try {
    file = write_data_file(partial.string(), grid, exports, record, eos, sigma, settings);
  } catch (const core::RunFailure& e) {
    ctx.abandon_output(data_name);
    // After a failed loop the fields may hold what the failed solve left (NaN past a fold): the run
    // has named its failure once already, so the missing file is a warning, not a second failure.
    if (record.failure.empty()) throw;
    ctx.log().warn("{} (the run failed before: {})", e.what(), record.failure);
    return;
  } catch (...) {
    ctx.abandon_output(data_name);
    throw;
  }
  ctx.commit_output(data_name);
  if (ctx.params().boolean("xdmf")) ctx.write_output(xdmf_name, xdmf_text(file, data_name));
  ctx.log().info("io_hdf5: {} ({} fields{}){}", data_name, file.datasets.size(),
                 settings.compression > 0 ? fmt::format(", deflate {}", settings.compression) : "",
                 ctx.params().boolean("xdmf") ? fmt::format(" and {}", xdmf_name) : "");
}

void declare(core::PluginBuilder& b) {
  b.require("grid");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    // One field at a time: the export's fill buffer and its stored points in C order.
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability))
      m.add(ctx.plugin(), "scratch", fmt::format("two finest-level arrays at {} while data.h5 is written", layout->describe()),
            2 * layout->field_bytes(core::Storage::finest_only));
  });
  b.integer("compression")
      .doc("deflate level of every dataset (with the shuffle filter), 0 for none; measured at n = 128: 0 writes "
           "268 MB in 1.1 s, 1 writes 139 MB in 5.1 s, 4 writes 137 MB in 6.3 s")
      .default_value(std::int64_t{1})
      .at_least(0)
      .at_most(9);
  b.keyword("variables", {"none", "unknowns", "all"})
      .doc("which of the solver's own fields (hatted units) to write under /variables as well: the elliptic "
           "equations' unknowns (chi, eta, wvec, beta: what a reader needs to add the puncture's 1/r exactly), "
           "every finest-level field, or none")
      .default_value(std::string("unknowns"));
  b.boolean("xdmf").doc("write data.xdmf beside data.h5, for ParaView and VisIt").default_value(true);
  b.schedule(Bin::output, "write", [](Context& ctx) { write(ctx); })
      .doc("data.h5 (atomically: data.h5.partial, fsync, rename) and data.xdmf; also after a failed loop, marked "
           "status = failed");
}

}  // namespace
}  // namespace bhnsid::io_hdf5

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "io_hdf5", "0.1",
                                     "data.h5 (Einstein Toolkit names, HDF5) and data.xdmf for evolution codes and viewers",
                                     &bhnsid::io_hdf5::declare};
  return &info;
}
