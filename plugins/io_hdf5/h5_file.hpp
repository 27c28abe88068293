#pragma once
// A small RAII layer over the HDF5 C API: a new file at a (temporary) path, groups, compressed 3-D
// datasets and attributes; every failure is a core::RunFailure naming what HDF5 could not do. The
// plugin writes to `data.h5.partial` and renames it into place only when it is complete.
#include <hdf5.h>

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace bhnsid::io_hdf5 {

/// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close, const std::string& what);
  Handle(Handle&& other) noexcept;
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle();
  hid_t id() const { return id_; }
  /// Gives up ownership (the caller closes it).
  hid_t release() { return std::exchange(id_, -1); }

 private:
  hid_t id_ = -1;
  Closer close_ = nullptr;
};

class H5File {
 public:
  /// A new file at `path` (replaced if it exists); HDF5's own error printing is turned off.
  explicit H5File(const std::string& path);
  /// The root group (attributes on it describe the file).
  hid_t root() const { return file_.id(); }
  /// A group at an absolute path whose parent exists ("/ADMBase").
  hid_t group(const std::string& path);
  /// A 3-D double dataset of shape dims (slowest first), chunked, shuffled and deflated at `level`
  /// (0: no compression), from `values` in C order.
  hid_t dataset(hid_t parent, const std::string& name, const std::array<hsize_t, 3>& dims, const std::vector<double>& values,
                int level);
  /// A second name for an existing object (an HDF5 hard link: the data are stored once).
  void link(const std::string& existing, const std::string& name);
  void attribute(hid_t object, const std::string& name, const std::string& value);
  void attribute(hid_t object, const std::string& name, double value);
  void attribute(hid_t object, const std::string& name, long long value);
  void attribute(hid_t object, const std::string& name, const std::vector<double>& values);
  /// Closes every object and the file, reporting a failure (a full disk) as an exception.
  void close();

 private:
  std::string path_;
  Handle file_;
  std::vector<Handle> open_;  // groups and datasets, closed with the file
};

}  // namespace bhnsid::io_hdf5
