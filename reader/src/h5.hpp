#pragma once
// The reader's only contact with HDF5. Debian's HDF5 is not built thread-safe, so every call into
// it, from any handle, holds one process-wide mutex (H5Lock); HDF5's own error printing is switched
// off for the duration and restored after, so that the library never writes to stderr and leaves
// the application's HDF5 settings as they were.
#include <hdf5.h>

#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace bhnsid::reader {

/// An error with the C status it maps to at the API boundary.
class Error : public std::runtime_error {
 public:
  Error(int code, const std::string& message) : std::runtime_error(message), code_(code) {}
  int code() const { return code_; }

 private:
  int code_;
};

/// Holds the process-wide HDF5 mutex and silences HDF5's error stack while alive.
class H5Lock {
 public:
  H5Lock();
  ~H5Lock();
  H5Lock(const H5Lock&) = delete;
  H5Lock& operator=(const H5Lock&) = delete;

 private:
  std::unique_lock<std::mutex> lock_;
  H5E_auto2_t saved_func_ = nullptr;
  void* saved_data_ = nullptr;
};

/// An HDF5 identifier closed by its own close function.
class H5Id {
 public:
  using Closer = herr_t (*)(hid_t);
  H5Id() = default;
  H5Id(hid_t id, Closer close) : id_(id), close_(close) {}
  H5Id(H5Id&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  H5Id& operator=(H5Id&& o) noexcept;
  H5Id(const H5Id&) = delete;
  H5Id& operator=(const H5Id&) = delete;
  ~H5Id();
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = -1;
  Closer close_ = nullptr;
};

// All functions below expect the caller to hold an H5Lock.

/// Opens `path` read-only; throws Error (ERR_IO) naming the cause: missing, unreadable, not HDF5.
H5Id open_file(const std::string& path);
bool has_object(hid_t file, const std::string& path);
bool has_attribute(hid_t file, const std::string& object, const std::string& name);
/// A string attribute (variable or fixed length); throws ERR_NOT_FOUND or ERR_FORMAT.
std::string string_attribute(hid_t file, const std::string& object, const std::string& name);
/// A numeric attribute (any integer or float type, any shape) as doubles.
std::vector<double> numeric_attribute(hid_t file, const std::string& object, const std::string& name);
/// Names of the numeric attributes of `object`, in HDF5's (alphabetical) order.
std::vector<std::string> numeric_attribute_names(hid_t file, const std::string& object);
/// Names of the datasets directly under the group `group` (none if it is absent).
std::vector<std::string> dataset_names(hid_t file, const std::string& group);
/// A 3-D double dataset of shape dims_zyx; throws ERR_FORMAT on another rank, shape or type.
std::vector<double> read_dataset(hid_t file, const std::string& path, const std::vector<hsize_t>& dims_zyx);

}  // namespace bhnsid::reader
