#pragma once
// One open data.h5: what open() checks and reads at once (root attributes, the grid, the scalars,
// the EOS, the list of datasets) and the datasets themselves, read on first use and kept in memory.
// After open every member is immutable except the caches, which one mutex guards; a dataset once
// loaded never changes or moves, so interpolation reads it without a lock.
#include <array>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "h5.hpp"

namespace bhnsid::reader {

struct Grid {
  int nx = 0, ny = 0, nz = 0;
  double dx = 0;
  std::array<double, 3> origin{};
  bool equatorial = false;
  /// The points' range per axis: index k runs over [kmin, nz - 1], kmin = -(nz - 1) by mirroring.
  int kmin() const { return equatorial ? -(nz - 1) : 0; }
  std::size_t at(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * static_cast<std::size_t>(ny) + static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(nx) +
           static_cast<std::size_t>(i);
  }
};

/// Where a dataset holds a set value instead of a solution (held_region_* attributes), physical.
struct HeldRegion {
  bool cube = true;  // else a sphere
  std::array<double, 3> centre{};
  double half_size = 0;
};

/// A dataset in memory, [k][j][i] over the stored points, with its mirror parity and, when it had
/// a held region, the region (already replaced by the harmonic fill).
struct Field {
  std::vector<double> values;
  int parity = 1;
  std::optional<HeldRegion> held;
  std::size_t filled_points = 0;
  /// Stored value at (i, j, k), k < 0 by mirroring.
  double value(const Grid& g, int i, int j, int k) const {
    return k >= 0 ? values[g.at(i, j, k)] : parity * values[g.at(i, j, -k)];
  }
};

/// /eos's formulas: piece i holds for rho_lo[i] <= rho < rho_lo[i + 1].
struct PiecewisePolytrope {
  std::vector<double> rho_lo, k, gamma, a;
};

class DataFile {
 public:
  explicit DataFile(const std::string& path);
  ~DataFile();

  const std::string& path() const { return path_; }
  const Grid& grid() const { return grid_; }
  /// Every 3-D dataset as a path ("/ADMBase/alp"), sorted.
  const std::vector<std::string>& datasets() const { return datasets_; }
  bool has_dataset(const std::string& path) const;
  /// The dataset, loaded (and filled) on first use; throws ERR_NOT_FOUND if absent. Thread-safe.
  const Field& field(const std::string& path) const;

  const std::vector<std::string>& scalar_names() const { return scalar_names_; }
  std::optional<double> scalar(const std::string& name) const;

  /// The EOS's formulas, or none with the reason in eos_problem().
  const std::optional<PiecewisePolytrope>& eos() const { return eos_; }
  const std::string& eos_problem() const { return eos_problem_; }

  /// Attributes of any object, read through HDF5 on each call (under the global lock); the
  /// string is cached so that the C API can hand out a pointer valid until close.
  const std::string& string_attribute(const std::string& object, const std::string& name) const;
  std::vector<double> numeric_attribute(const std::string& object, const std::string& name) const;

 private:
  std::unique_ptr<Field> load(const std::string& path) const;
  void read_grid();
  void read_eos();

  std::string path_;
  H5Id file_;
  Grid grid_;
  std::vector<std::string> datasets_;
  std::vector<std::string> scalar_names_;
  std::map<std::string, double> scalars_;
  std::optional<PiecewisePolytrope> eos_;
  std::string eos_problem_;

  mutable std::mutex cache_mutex_;
  mutable std::map<std::string, std::unique_ptr<Field>> fields_;
  mutable std::map<std::pair<std::string, std::string>, std::unique_ptr<std::string>> strings_;
};

}  // namespace bhnsid::reader
