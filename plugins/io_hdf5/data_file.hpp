#pragma once
// The layout of data.h5 (docs/output-format.md, format_version 1): what goes where, from the grid,
// the published FieldExport services and the core's run record.
#include <array>
#include <string>
#include <vector>

#include "bhnsid/core/context.hpp"
#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::io_hdf5 {

inline constexpr long long format_version = 1;

struct Settings {
  int compression = 4;    ///< deflate level, 0 none
  /// The code's own (hatted) fields to write under /variables; all = every finest-level field.
  std::vector<std::string> variables;
  bool all_variables = false;
};

/// The stored points of the finest level in physical coordinates (x = sigma xhat).
struct Geometry {
  int nx = 0, ny = 0, nz = 0;
  double dx = 0;
  std::array<double, 3> origin{};
};

struct EosRecord {
  const Eos* eos = nullptr;  ///< null without an EOS plugin (vacuum runs)
  std::string plugin;
};

struct DataFile {
  std::vector<std::string> datasets;  ///< every 3-D dataset's path, in the order written
  Geometry geometry;
};

/// Writes the file at `path`. Throws core::RunFailure naming the dataset and the point when a value
/// is not finite (the caller then removes the unfinished file: it never holds garbage).
DataFile write_data_file(const std::string& path, const Grid& grid, const std::vector<const FieldExport*>& exports, const core::RunRecord& record,
                         const EosRecord& eos, double sigma, const Settings& settings);

}  // namespace bhnsid::io_hdf5
