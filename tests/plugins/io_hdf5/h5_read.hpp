#pragma once
// Reading data.h5 in the tests with the HDF5 C API alone (no code of the plugin's): what an
// evolution code's importer would do.
#include <hdf5.h>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace bhnsid::test {

class H5Reader {
 public:
  explicit H5Reader(const std::string& path) : file_(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {
    if (file_ < 0) throw std::runtime_error("cannot open " + path);
  }
  ~H5Reader() { H5Fclose(file_); }
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  bool exists(const std::string& path) const {
    std::string prefix;
    for (std::size_t at = 1; at != std::string::npos;) {
      const std::size_t next = path.find('/', at);
      prefix = path.substr(0, next);
      if (H5Lexists(file_, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
      at = next == std::string::npos ? next : next + 1;
    }
    return true;
  }

  /// A 3-D dataset, its dims slowest first.
  std::vector<double> dataset(const std::string& path, std::array<hsize_t, 3>& dims) const {
    const hid_t d = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    if (d < 0) throw std::runtime_error("no dataset " + path);
    const hid_t space = H5Dget_space(d);
    if (H5Sget_simple_extent_ndims(space) != 3) throw std::runtime_error(path + " is not 3-D");
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    std::vector<double> out(dims[0] * dims[1] * dims[2]);
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
    H5Sclose(space);
    H5Dclose(d);
    return out;
  }

  /// The filters of a dataset (H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE, ...).
  std::vector<H5Z_filter_t> filters(const std::string& path) const {
    const hid_t d = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    const hid_t plist = H5Dget_create_plist(d);
    std::vector<H5Z_filter_t> out;
    for (int f = 0; f < H5Pget_nfilters(plist); ++f) {
      unsigned flags = 0;
      std::size_t n = 0;
      unsigned config = 0;
      out.push_back(H5Pget_filter2(plist, static_cast<unsigned>(f), &flags, &n, nullptr, 0, nullptr, &config));
    }
    H5Pclose(plist);
    H5Dclose(d);
    return out;
  }

  bool exists_attribute(const std::string& object, const std::string& name) const {
    return H5Aexists_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
  }

  double real(const std::string& object, const std::string& name) const {
    double v = 0;
    const hid_t a = H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0) throw std::runtime_error("no attribute " + object + " " + name);
    H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
    return v;
  }

  std::vector<double> reals(const std::string& object, const std::string& name, std::size_t n) const {
    std::vector<double> v(n);
    const hid_t a = H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0) throw std::runtime_error("no attribute " + object + " " + name);
    H5Aread(a, H5T_NATIVE_DOUBLE, v.data());
    H5Aclose(a);
    return v;
  }

  long long integer(const std::string& object, const std::string& name) const {
    long long v = 0;
    const hid_t a = H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0) throw std::runtime_error("no attribute " + object + " " + name);
    H5Aread(a, H5T_NATIVE_LLONG, &v);
    H5Aclose(a);
    return v;
  }

  std::string text(const std::string& object, const std::string& name) const {
    const hid_t a = H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0) throw std::runtime_error("no attribute " + object + " " + name);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    char* value = nullptr;
    H5Aread(a, type, &value);
    std::string out = value ? value : "";
    H5free_memory(value);
    H5Tclose(type);
    H5Aclose(a);
    return out;
  }

 private:
  hid_t file_;
};

}  // namespace bhnsid::test
