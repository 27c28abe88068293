#include "h5.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <new>
#include <utility>

#include "bhnsid_reader.h"

namespace bhnsid::reader {

namespace {

std::mutex& h5_mutex() {
  static std::mutex m;
  return m;
}

hid_t checked(hid_t id, int code, const std::string& what) {
  if (id < 0) throw Error(code, what);
  return id;
}

/// Whether every link on the way to `path` exists (H5Oexists_by_name fails on a missing parent).
bool path_exists(hid_t file, const std::string& path) {
  if (path == "/") return true;
  std::size_t pos = 0;
  while (pos != std::string::npos) {
    pos = path.find('/', pos + 1);
    const std::string prefix = path.substr(0, pos);
    if (prefix.empty() || prefix == "/") continue;
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return H5Oexists_by_name(file, path.c_str(), H5P_DEFAULT) > 0;
}

H5Id open_attribute(hid_t file, const std::string& object, const std::string& name) {
  if (!has_attribute(file, object, name))
    throw Error(BHNSID_READER_ERR_NOT_FOUND, "no attribute " + object + "@" + name + " in the file");
  return H5Id(checked(H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                      BHNSID_READER_ERR_FORMAT, "HDF5 could not open the attribute " + object + "@" + name),
              H5Aclose);
}

bool is_numeric(hid_t type) {
  const H5T_class_t c = H5Tget_class(type);
  return c == H5T_INTEGER || c == H5T_FLOAT;
}

}  // namespace

H5Lock::H5Lock() : lock_(h5_mutex()) {
  H5Eget_auto2(H5E_DEFAULT, &saved_func_, &saved_data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

H5Lock::~H5Lock() { H5Eset_auto2(H5E_DEFAULT, saved_func_, saved_data_); }

H5Id& H5Id::operator=(H5Id&& o) noexcept {
  std::swap(id_, o.id_);
  std::swap(close_, o.close_);
  return *this;
}

H5Id::~H5Id() {
  if (id_ >= 0 && close_) close_(id_);
}

H5Id open_file(const std::string& path) {
  // Opened non-blocking and checked with fstat before HDF5 sees the path: a FIFO would otherwise
  // hold the caller until something writes to it, and a device would be read without end.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int e = errno;
    if (e == ENOENT) throw Error(BHNSID_READER_ERR_IO, "no such file: " + path);
    throw Error(BHNSID_READER_ERR_IO, "cannot read " + path + ": " + std::strerror(e));
  }
  struct stat st {};
  const bool stat_ok = ::fstat(fd, &st) == 0;
  ::close(fd);
  if (!stat_ok) throw Error(BHNSID_READER_ERR_IO, "cannot examine " + path);
  if (S_ISDIR(st.st_mode)) throw Error(BHNSID_READER_ERR_IO, path + " is a directory, not a data.h5");
  if (!S_ISREG(st.st_mode)) {
    const char* kind = S_ISFIFO(st.st_mode) ? "a FIFO" : S_ISSOCK(st.st_mode) ? "a socket" : "a device";
    throw Error(BHNSID_READER_ERR_IO, path + " is " + kind + ", not a regular file");
  }
  const htri_t is_h5 = H5Fis_hdf5(path.c_str());
  if (is_h5 <= 0) throw Error(BHNSID_READER_ERR_IO, path + " is not an HDF5 file");
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw Error(BHNSID_READER_ERR_IO, "HDF5 could not open " + path + " (damaged or locked?)");
  return H5Id(f, H5Fclose);
}

bool has_object(hid_t file, const std::string& path) { return path_exists(file, path); }

bool has_attribute(hid_t file, const std::string& object, const std::string& name) {
  if (!path_exists(file, object)) return false;
  return H5Aexists_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

std::string string_attribute(hid_t file, const std::string& object, const std::string& name) {
  const H5Id attr = open_attribute(file, object, name);
  const std::string where = object + "@" + name;
  const H5Id type(checked(H5Aget_type(attr.get()), BHNSID_READER_ERR_FORMAT, "no type for " + where), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING) throw Error(BHNSID_READER_ERR_FORMAT, where + " is not a string");
  const H5Id space(checked(H5Aget_space(attr.get()), BHNSID_READER_ERR_FORMAT, "no dataspace for " + where), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1)
    throw Error(BHNSID_READER_ERR_FORMAT, where + " is not a single string");
  if (H5Tis_variable_str(type.get()) > 0) {
    const H5Id mem(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(mem.get(), H5T_VARIABLE);
    H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
    char* text = nullptr;
    if (H5Aread(attr.get(), mem.get(), &text) < 0) throw Error(BHNSID_READER_ERR_FORMAT, "cannot read " + where);
    std::string out = text ? text : "";
    H5Dvlen_reclaim(mem.get(), space.get(), H5P_DEFAULT, &text);
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  std::string out(size, '\0');
  if (H5Aread(attr.get(), type.get(), out.data()) < 0) throw Error(BHNSID_READER_ERR_FORMAT, "cannot read " + where);
  // Fixed-length strings are padded with NULs or spaces.
  const std::size_t end = out.find('\0');
  if (end != std::string::npos) out.resize(end);
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::vector<double> numeric_attribute(hid_t file, const std::string& object, const std::string& name) {
  const H5Id attr = open_attribute(file, object, name);
  const std::string where = object + "@" + name;
  const H5Id type(checked(H5Aget_type(attr.get()), BHNSID_READER_ERR_FORMAT, "no type for " + where), H5Tclose);
  if (!is_numeric(type.get())) throw Error(BHNSID_READER_ERR_FORMAT, where + " is not a number");
  const H5Id space(checked(H5Aget_space(attr.get()), BHNSID_READER_ERR_FORMAT, "no dataspace for " + where), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) throw Error(BHNSID_READER_ERR_FORMAT, "no size for " + where);
  std::vector<double> out(static_cast<std::size_t>(n));
  if (n > 0 && H5Aread(attr.get(), H5T_NATIVE_DOUBLE, out.data()) < 0)
    throw Error(BHNSID_READER_ERR_FORMAT, "cannot read " + where + " as doubles");
  return out;
}

std::vector<std::string> numeric_attribute_names(hid_t file, const std::string& object) {
  std::vector<std::string> names;
  if (!path_exists(file, object)) return names;
  const H5Id obj(checked(H5Oopen(file, object.c_str(), H5P_DEFAULT), BHNSID_READER_ERR_FORMAT, "cannot open " + object),
                 H5Oclose);
  struct Visit {
    static herr_t call(hid_t loc, const char* name, const H5A_info_t*, void* data) {
      const H5Id attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
      if (!attr.valid()) return 0;
      const H5Id type(H5Aget_type(attr.get()), H5Tclose);
      if (type.valid() && is_numeric(type.get())) static_cast<std::vector<std::string>*>(data)->push_back(name);
      return 0;
    }
  };
  hsize_t idx = 0;
  if (H5Aiterate2(obj.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, &Visit::call, &names) < 0)
    throw Error(BHNSID_READER_ERR_FORMAT, "cannot list the attributes of " + object);
  return names;
}

std::vector<std::string> dataset_names(hid_t file, const std::string& group) {
  std::vector<std::string> names;
  if (!path_exists(file, group)) return names;
  const H5Id g(H5Gopen2(file, group.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) return names;  // a dataset or type of that name, not a group: nothing to list
  H5G_info_t info;
  if (H5Gget_info(g.get(), &info) < 0) throw Error(BHNSID_READER_ERR_FORMAT, "cannot list " + group);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t len = H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) throw Error(BHNSID_READER_ERR_FORMAT, "cannot name a member of " + group);
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(len));
    const H5Id obj(H5Oopen(g.get(), name.c_str(), H5P_DEFAULT), H5Oclose);
    if (obj.valid() && H5Iget_type(obj.get()) == H5I_DATASET) names.push_back(name);
  }
  return names;
}

std::vector<double> read_dataset(hid_t file, const std::string& path, const std::vector<hsize_t>& dims_zyx) {
  if (!path_exists(file, path)) throw Error(BHNSID_READER_ERR_NOT_FOUND, "no dataset " + path + " in the file");
  const H5Id d(checked(H5Dopen2(file, path.c_str(), H5P_DEFAULT), BHNSID_READER_ERR_FORMAT, "cannot open " + path),
               H5Dclose);
  const H5Id type(checked(H5Dget_type(d.get()), BHNSID_READER_ERR_FORMAT, "no type for " + path), H5Tclose);
  if (!is_numeric(type.get())) throw Error(BHNSID_READER_ERR_FORMAT, path + " does not hold numbers");
  const H5Id space(checked(H5Dget_space(d.get()), BHNSID_READER_ERR_FORMAT, "no dataspace for " + path), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  hsize_t dims[3] = {0, 0, 0};
  if (rank != 3 || H5Sget_simple_extent_dims(space.get(), dims, nullptr) != 3)
    throw Error(BHNSID_READER_ERR_FORMAT, path + " is not a 3-D dataset");
  for (int a = 0; a < 3; ++a)
    if (dims[a] != dims_zyx[static_cast<std::size_t>(a)])
      throw Error(BHNSID_READER_ERR_FORMAT, path + " has shape " + std::to_string(dims[0]) + " x " +
                                                std::to_string(dims[1]) + " x " + std::to_string(dims[2]) +
                                                ", not /grid@shape_zyx");
  // dims come from the file: a damaged or hostile one may claim more points than any memory holds.
  const double bytes = 8.0 * double(dims[0]) * double(dims[1]) * double(dims[2]);
  const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  const auto out_of_memory = [&] {
    char size[64];
    std::snprintf(size, sizeof size, "%.3g GiB", bytes / 1073741824.0);
    return Error(BHNSID_READER_ERR_INTERNAL, "out of memory: " + path + " holds " + std::to_string(dims[0]) + " x " +
                                                 std::to_string(dims[1]) + " x " + std::to_string(dims[2]) +
                                                 " doubles (" + size + "), more than this machine can hold");
  };
  if (physical > 0 && bytes > physical) throw out_of_memory();
  std::vector<double> out;
  try {
    out.resize(dims[0] * dims[1] * dims[2]);
  } catch (const std::bad_alloc&) {
    throw out_of_memory();
  }
  if (H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw Error(BHNSID_READER_ERR_IO, "HDF5 could not read " + path + " (damaged file?)");
  return out;
}

}  // namespace bhnsid::reader
