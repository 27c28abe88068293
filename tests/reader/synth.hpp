#pragma once
// Synthetic data.h5 files for the reader's tests, written with the HDF5 C API in the layout of
// docs/output-format.md: root attributes, /grid, datasets with parity_z, /scalars, /eos. A test
// describes the grid and gives each field as a function of the physical coordinates.
#include <hdf5.h>

#include <array>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace synth {

struct GridSpec {
  int nx = 17, ny = 17, nz = 17;
  double dx = 0.1;
  std::array<double, 3> origin{-0.8, -0.8, -0.8};
  bool equatorial = false;  // then origin z must be 0
};

using Fn = std::function<double(double x, double y, double z)>;

struct Held {
  std::string shape = "cube";
  std::array<double, 3> centre{};
  double half_size = 0;
};

struct DatasetSpec {
  Fn fn;
  int parity = 1;
  const Held* held = nullptr;
};

class Writer {
 public:
  explicit Writer(const std::string& path) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (file_ < 0) throw std::runtime_error("synth: cannot create " + path);
  }
  ~Writer() {
    for (hid_t g : groups_) H5Gclose(g);
    if (file_ >= 0) H5Fclose(file_);
  }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  /// The root attributes and /grid of a valid file (format "bhnsid-data", version 1).
  void header(const GridSpec& g, const std::string& format = "bhnsid-data", long long version = 1) {
    grid_ = g;
    string_attr(file_, "format", format);
    int_attr(file_, "format_version", version);
    string_attr(file_, "status", "converged");
    string_attr(file_, "failure", "");
    string_attr(file_, "units", "G = c = 1");
    const hid_t gr = group("/grid");
    doubles_attr(gr, "shape_zyx", {double(g.nz), double(g.ny), double(g.nx)});
    doubles_attr(gr, "dx", {g.dx});
    doubles_attr(gr, "origin_xyz", {g.origin[0], g.origin[1], g.origin[2]});
    doubles_attr(gr, "sigma", {1.0});
    doubles_attr(gr, "dx_hat", {g.dx});
    string_attr(gr, "symmetry", g.equatorial ? "equatorial" : "none");
    string_attr(gr, "layout", "vertex-centred uniform grid");
  }

  /// A dataset at path ("/ADMBase/alp") holding fn at the stored points.
  void dataset(const std::string& path, const DatasetSpec& d) {
    ensure_parent(path);
    std::vector<double> v(static_cast<std::size_t>(grid_.nx) * grid_.ny * grid_.nz);
    std::size_t q = 0;
    for (int k = 0; k < grid_.nz; ++k)
      for (int j = 0; j < grid_.ny; ++j)
        for (int i = 0; i < grid_.nx; ++i)
          v[q++] = d.fn(grid_.origin[0] + grid_.dx * i, grid_.origin[1] + grid_.dx * j, grid_.origin[2] + grid_.dx * k);
    const hsize_t dims[3] = {hsize_t(grid_.nz), hsize_t(grid_.ny), hsize_t(grid_.nx)};
    const hid_t space = H5Screate_simple(3, dims, nullptr);
    const hid_t ds = H5Dcreate2(file_, path.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (ds < 0) throw std::runtime_error("synth: cannot create " + path);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    int_attr(ds, "parity_z", d.parity);
    string_attr(ds, "units", "1");
    if (d.held) {
      string_attr(ds, "held_region_shape", d.held->shape);
      doubles_attr(ds, "held_region_centre", {d.held->centre[0], d.held->centre[1], d.held->centre[2]});
      doubles_attr(ds, "held_region_half_size", {d.held->half_size});
    }
    H5Dclose(ds);
    H5Sclose(space);
  }

  void link(const std::string& existing, const std::string& path) {
    H5Lcreate_hard(file_, existing.c_str(), file_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  }

  void scalar(const std::string& name, double v) { doubles_attr(group("/scalars"), name, {v}); }

  /// /eos with the piecewise-polytrope formulas (empty model: no `model` attribute at all).
  void eos(const std::string& model, const std::vector<double>& rho_lo, const std::vector<double>& k,
           const std::vector<double>& gamma, const std::vector<double>& a) {
    const hid_t e = group("/eos");
    string_attr(e, "plugin", "synthetic");
    string_attr(e, "description", "synthetic EOS for the reader's tests");
    if (model.empty()) return;
    string_attr(e, "model", model);
    doubles_attr(e, "rho0_lo", rho_lo);
    doubles_attr(e, "K", k);
    doubles_attr(e, "Gamma", gamma);
    doubles_attr(e, "eps_offset", a);
  }

 private:
  hid_t group(const std::string& path) {
    const auto it = named_.find(path);
    if (it != named_.end()) return it->second;
    const hid_t g = H5Gcreate2(file_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) throw std::runtime_error("synth: cannot create group " + path);
    groups_.push_back(g);
    named_[path] = g;
    return g;
  }
  void ensure_parent(const std::string& path) { group(path.substr(0, path.rfind('/'))); }

  static void string_attr(hid_t obj, const std::string& name, const std::string& value) {
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = value.c_str();
    H5Awrite(a, type, &text);
    H5Aclose(a);
    H5Sclose(space);
    H5Tclose(type);
  }
  static void int_attr(hid_t obj, const std::string& name, long long value) {
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(obj, name.c_str(), H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_LLONG, &value);
    H5Aclose(a);
    H5Sclose(space);
  }
  static void doubles_attr(hid_t obj, const std::string& name, const std::vector<double>& v) {
    const hsize_t n = v.size();
    const hid_t space = n == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr);
    const hid_t a = H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_DOUBLE, v.data());
    H5Aclose(a);
    H5Sclose(space);
  }

  hid_t file_ = -1;
  GridSpec grid_;
  std::vector<hid_t> groups_;
  std::map<std::string, hid_t> named_;
};

}  // namespace synth
