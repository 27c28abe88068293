#include "h5_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::io_hdf5 {

namespace {

hid_t checked(hid_t id, const std::string& what) {
  if (id < 0) throw core::RunFailure(fmt::format("io_hdf5: HDF5 could not {}", what));
  return id;
}

void checked(herr_t status, const std::string& what) {
  if (status < 0) throw core::RunFailure(fmt::format("io_hdf5: HDF5 could not {}", what));
}

}  // namespace

Handle::Handle(hid_t id, Closer close, const std::string& what) : id_(checked(id, what)), close_(close) {}
Handle::Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), close_(other.close_) {}
Handle& Handle::operator=(Handle&& other) noexcept {
  std::swap(id_, other.id_);
  std::swap(close_, other.close_);
  return *this;
}
Handle::~Handle() {
  if (id_ >= 0 && close_) close_(id_);
}

H5File::H5File(const std::string& path) : path_(path) {
  // A write the disk refused leaves the file open inside HDF5 (its close fails too), and HDF5's exit
  // handler then crashed closing it again (exit 139 after a clear error). Every file that matters is
  // closed here; the library need not clean up at exit. Only the first call, before HDF5 starts, counts.
  static const bool no_exit_handler = H5dont_atexit() >= 0;
  (void)no_exit_handler;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  file_ = Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, "create " + path);
}

hid_t H5File::group(const std::string& path) {
  open_.emplace_back(H5Gcreate2(file_.id(), path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                     "create the group " + path);
  return open_.back().id();
}

hid_t H5File::dataset(hid_t parent, const std::string& name, const std::array<hsize_t, 3>& dims,
                         const std::vector<double>& values, int level) {
  Handle space(H5Screate_simple(3, dims.data(), nullptr), H5Sclose, "create a dataspace for " + name);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "create a dataset property list");
  if (level > 0) {
    // Chunks of whole planes, 4 at a time: about 2 MiB at n = 256, and a slice reads few chunks.
    const std::array<hsize_t, 3> chunk{std::min<hsize_t>(dims[0], 4), dims[1], dims[2]};
    checked(H5Pset_chunk(dcpl.id(), 3, chunk.data()), "set the chunks of " + name);
    checked(H5Pset_shuffle(dcpl.id()), "set the shuffle filter of " + name);
    checked(H5Pset_deflate(dcpl.id(), static_cast<unsigned>(level)), "set the deflate filter of " + name);
  }
  open_.emplace_back(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, dcpl.id(), H5P_DEFAULT),
                     H5Dclose, "create the dataset " + name);
  checked(H5Dwrite(open_.back().id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          "write the dataset " + name);
  return open_.back().id();
}

void H5File::link(const std::string& existing, const std::string& name) {
  checked(H5Lcreate_hard(file_.id(), existing.c_str(), file_.id(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
          "link " + name + " to " + existing);
}

void H5File::attribute(hid_t object, const std::string& name, const std::string& value) {
  // Variable-length UTF-8: h5py reads it as a str, C readers as a char* (H5Dvlen_reclaim frees it).
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy the string type");
  checked(H5Tset_size(type.id(), H5T_VARIABLE), "size a string type");
  checked(H5Tset_cset(type.id(), H5T_CSET_UTF8), "set a string's character set");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create a scalar dataspace");
  Handle attr(H5Acreate2(object, name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "create the attribute " + name);
  const char* text = value.c_str();
  checked(H5Awrite(attr.id(), type.id(), &text), "write the attribute " + name);
}

void H5File::attribute(hid_t object, const std::string& name, double value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create a scalar dataspace");
  Handle attr(H5Acreate2(object, name.c_str(), H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "create the attribute " + name);
  checked(H5Awrite(attr.id(), H5T_NATIVE_DOUBLE, &value), "write the attribute " + name);
}

void H5File::attribute(hid_t object, const std::string& name, long long value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create a scalar dataspace");
  Handle attr(H5Acreate2(object, name.c_str(), H5T_STD_I64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "create the attribute " + name);
  checked(H5Awrite(attr.id(), H5T_NATIVE_LLONG, &value), "write the attribute " + name);
}

void H5File::attribute(hid_t object, const std::string& name, const std::vector<double>& values) {
  const hsize_t n = values.size();
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose, "create a dataspace");
  Handle attr(H5Acreate2(object, name.c_str(), H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              "create the attribute " + name);
  checked(H5Awrite(attr.id(), H5T_NATIVE_DOUBLE, values.data()), "write the attribute " + name);
}

void H5File::close() {
  open_.clear();
  checked(H5Fflush(file_.id(), H5F_SCOPE_GLOBAL), "write " + path_ + " (is the disk full?)");
  checked(H5Fclose(file_.release()), "close " + path_ + " (is the disk full?)");
}

}  // namespace bhnsid::io_hdf5
