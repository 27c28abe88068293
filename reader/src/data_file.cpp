#include "data_file.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bhnsid_reader.h"
#include "fill.hpp"

namespace bhnsid::reader {

namespace {

constexpr long long supported_version = 1;

std::string number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

Error format_error(const std::string& path, const std::string& what) {
  return Error(BHNSID_READER_ERR_FORMAT, path + ": " + what);
}

}  // namespace

DataFile::DataFile(const std::string& path) : path_(path) {
  H5Lock lock;
  file_ = open_file(path);
  const hid_t f = file_.get();
  if (!has_attribute(f, "/", "format"))
    throw format_error(path, "not a bhnsid data.h5 (no root attribute 'format')");
  const std::string format = reader::string_attribute(f, "/", "format");
  if (format != "bhnsid-data")
    throw format_error(path, "format is '" + format + "', not 'bhnsid-data': not a bhnsid data file");
  if (!has_attribute(f, "/", "format_version")) throw format_error(path, "no root attribute 'format_version'");
  const std::vector<double> version = reader::numeric_attribute(f, "/", "format_version");
  if (version.size() != 1) throw format_error(path, "format_version is not a single number");
  if (version[0] > supported_version)
    throw format_error(path, "format_version " + number(version[0]) +
                                 " is newer than this reader understands (1): use a newer bhnsid reader");
  if (version[0] != supported_version)
    throw format_error(path, "format_version " + number(version[0]) + " is not supported (this reader reads 1)");

  read_grid();
  for (const char* group : {"ADMBase", "HydroBase", "variables"})
    for (const std::string& name : dataset_names(f, std::string("/") + group))
      datasets_.push_back(std::string("/") + group + "/" + name);
  std::sort(datasets_.begin(), datasets_.end());

  for (const std::string& name : numeric_attribute_names(f, "/scalars")) {
    const std::vector<double> v = reader::numeric_attribute(f, "/scalars", name);
    if (v.size() != 1) continue;  // not a scalar: reachable through numeric_attribute()
    scalar_names_.push_back(name);
    scalars_[name] = v[0];
  }
  read_eos();
}

DataFile::~DataFile() {
  H5Lock lock;
  file_ = H5Id();
}

void DataFile::read_grid() {
  const hid_t f = file_.get();
  if (!has_object(f, "/grid")) throw format_error(path_, "no group /grid");
  const std::vector<double> shape = reader::numeric_attribute(f, "/grid", "shape_zyx");
  if (shape.size() != 3) throw format_error(path_, "/grid@shape_zyx does not hold 3 numbers");
  for (double s : shape)
    if (!(s >= 1 && s <= 1e6 && s == std::floor(s)))
      throw format_error(path_, "/grid@shape_zyx holds " + number(s) + ", not a positive integer");
  grid_.nz = static_cast<int>(shape[0]);
  grid_.ny = static_cast<int>(shape[1]);
  grid_.nx = static_cast<int>(shape[2]);
  const std::vector<double> dx = reader::numeric_attribute(f, "/grid", "dx");
  if (dx.size() != 1 || !(dx[0] > 0) || !std::isfinite(dx[0]))
    throw format_error(path_, "/grid@dx is not one positive number");
  grid_.dx = dx[0];
  const std::vector<double> origin = reader::numeric_attribute(f, "/grid", "origin_xyz");
  if (origin.size() != 3) throw format_error(path_, "/grid@origin_xyz does not hold 3 numbers");
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(origin[static_cast<std::size_t>(a)]))
      throw format_error(path_, "/grid@origin_xyz is not finite");
    grid_.origin[static_cast<std::size_t>(a)] = origin[static_cast<std::size_t>(a)];
  }
  const std::string symmetry = reader::string_attribute(f, "/grid", "symmetry");
  if (symmetry == "equatorial")
    grid_.equatorial = true;
  else if (symmetry != "none")
    throw format_error(path_, "/grid@symmetry is '" + symmetry + "' (this reader knows 'equatorial' and 'none')");
  if (grid_.equatorial && std::fabs(grid_.origin[2]) > 1e-12 * grid_.dx)
    throw format_error(path_, "equatorial symmetry with origin z = " + number(grid_.origin[2]) + " (must be 0)");
}

void DataFile::read_eos() {
  const hid_t f = file_.get();
  if (!has_attribute(f, "/eos", "model")) {
    eos_problem_ = "the file's /eos has no 'model' attribute (written before the EOS formulas were stored)";
    return;
  }
  const std::string model = reader::string_attribute(f, "/eos", "model");
  if (model != "piecewise_polytrope") {
    eos_problem_ = "the file's EOS is of model '" + model + "', which this reader cannot evaluate";
    return;
  }
  PiecewisePolytrope eos;
  eos.rho_lo = reader::numeric_attribute(f, "/eos", "rho0_lo");
  eos.k = reader::numeric_attribute(f, "/eos", "K");
  eos.gamma = reader::numeric_attribute(f, "/eos", "Gamma");
  eos.a = reader::numeric_attribute(f, "/eos", "eps_offset");
  const std::size_t n = eos.rho_lo.size();
  if (n == 0 || eos.k.size() != n || eos.gamma.size() != n || eos.a.size() != n)
    throw format_error(path_, "/eos: rho0_lo, K, Gamma and eps_offset must be non-empty and of one length");
  if (eos.rho_lo[0] != 0) throw format_error(path_, "/eos@rho0_lo must start at 0");
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && !(eos.rho_lo[i] > eos.rho_lo[i - 1]))
      throw format_error(path_, "/eos@rho0_lo must increase");
    if (!(eos.k[i] > 0) || !(eos.gamma[i] > 1) || !std::isfinite(eos.k[i]) || !std::isfinite(eos.gamma[i]) ||
        !std::isfinite(eos.a[i]))
      throw format_error(path_, "/eos: piece " + std::to_string(i) + " needs K > 0, Gamma > 1 and a finite offset");
  }
  eos_ = std::move(eos);
}

bool DataFile::has_dataset(const std::string& path) const {
  return std::binary_search(datasets_.begin(), datasets_.end(), path);
}

std::optional<double> DataFile::scalar(const std::string& name) const {
  const auto it = scalars_.find(name);
  if (it == scalars_.end()) return std::nullopt;
  return it->second;
}

const Field& DataFile::field(const std::string& path) const {
  std::lock_guard<std::mutex> guard(cache_mutex_);
  auto it = fields_.find(path);
  if (it == fields_.end()) it = fields_.emplace(path, load(path)).first;
  return *it->second;
}

std::unique_ptr<Field> DataFile::load(const std::string& path) const {
  if (!has_dataset(path)) throw Error(BHNSID_READER_ERR_NOT_FOUND, "no dataset " + path + " in " + path_);
  auto field = std::make_unique<Field>();
  {
    H5Lock lock;
    const hid_t f = file_.get();
    field->values = read_dataset(f, path, {hsize_t(grid_.nz), hsize_t(grid_.ny), hsize_t(grid_.nx)});
    if (has_attribute(f, path, "parity_z")) {
      const std::vector<double> p = reader::numeric_attribute(f, path, "parity_z");
      if (p.size() != 1 || (p[0] != 1 && p[0] != -1)) throw format_error(path_, path + "@parity_z is not 1 or -1");
      field->parity = static_cast<int>(p[0]);
    } else if (grid_.equatorial) {
      throw format_error(path_, path + " has no parity_z, which equatorial symmetry needs");
    }
    if (has_attribute(f, path, "held_region_shape")) {
      HeldRegion r;
      const std::string shape = reader::string_attribute(f, path, "held_region_shape");
      if (shape != "cube" && shape != "sphere")
        throw format_error(path_, path + "@held_region_shape is '" + shape + "', not 'cube' or 'sphere'");
      r.cube = shape == "cube";
      const std::vector<double> c = reader::numeric_attribute(f, path, "held_region_centre");
      const std::vector<double> h = reader::numeric_attribute(f, path, "held_region_half_size");
      if (c.size() != 3 || h.size() != 1 || !(h[0] >= 0) || !std::isfinite(h[0]) || !std::isfinite(c[0]) ||
          !std::isfinite(c[1]) || !std::isfinite(c[2]))
        throw format_error(path_, path + ": held_region_centre (3 numbers) or held_region_half_size (>= 0) is malformed");
      r.centre = {c[0], c[1], c[2]};
      r.half_size = h[0];
      field->held = r;
    }
  }
  for (std::size_t p = 0; p < field->values.size(); ++p)
    if (!std::isfinite(field->values[p]))
      throw format_error(path_, path + " holds a non-finite value at flat index " + std::to_string(p));
  if (field->held) field->filled_points = harmonic_fill(grid_, *field->held, field->parity, field->values, path);
  return field;
}

const std::string& DataFile::string_attribute(const std::string& object, const std::string& name) const {
  std::lock_guard<std::mutex> guard(cache_mutex_);
  const auto key = std::make_pair(object, name);
  auto it = strings_.find(key);
  if (it == strings_.end()) {
    H5Lock lock;
    it = strings_.emplace(key, std::make_unique<std::string>(reader::string_attribute(file_.get(), object, name))).first;
  }
  return *it->second;
}

std::vector<double> DataFile::numeric_attribute(const std::string& object, const std::string& name) const {
  H5Lock lock;
  return reader::numeric_attribute(file_.get(), object, name);
}

}  // namespace bhnsid::reader
