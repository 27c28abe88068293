// axis_x.tsv against data.h5: the same published fields, the same points, two writers.
#include <catch2/catch.hpp>

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "process.hpp"

using namespace bhnsid::test;

namespace {

std::vector<double> h5_row(hid_t file, const std::string& path, hsize_t& nx) {
  const hid_t d = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  REQUIRE(d >= 0);
  const hid_t space = H5Dget_space(d);
  hsize_t dims[3];
  H5Sget_simple_extent_dims(space, dims, nullptr);
  std::vector<double> all(dims[0] * dims[1] * dims[2]);
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data());
  H5Sclose(space);
  H5Dclose(d);
  nx = dims[2];
  const hsize_t j = dims[1] / 2;  // k = 0 (z = 0, equatorial symmetry), the middle row in y
  return std::vector<double>(all.begin() + static_cast<std::ptrdiff_t>(j * nx),
                             all.begin() + static_cast<std::ptrdiff_t>((j + 1) * nx));
}

}  // namespace

TEST_CASE("plugins.io_ascii.axis_table_matches_data_h5", "[plugins][io_ascii]") {
  TempDir dir;
  const std::string text = read_file(source_dir() / "parfiles" / "quickstart.yaml");
  const auto at = text.find("io_hdf5]");
  REQUIRE(at != std::string::npos);
  const auto parfile = dir.write("q.yaml", text.substr(0, at) + "io_hdf5, io_ascii]" + text.substr(at + 8));
  const auto out = dir.path() / "run";
  const ProcessResult r = run_bhnsid({"run", parfile.string(), "--output", out.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  std::istringstream in(read_file(out / "axis_x.tsv"));
  std::string line, header;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    if (line.rfind("# x", 0) == 0) header = line.substr(2);
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    rows.emplace_back();
    for (std::string cell; std::getline(row, cell, '\t');) rows.back().push_back(std::stod(cell));
  }
  std::vector<std::string> names;
  std::istringstream h(header);
  for (std::string cell; std::getline(h, cell, '\t');) names.push_back(cell);
  REQUIRE(names.size() > 20);
  CHECK(std::count(names.begin(), names.end(), "ADMBase::alp") == 1);
  CHECK(std::count(names.begin(), names.end(), "HydroBase::rho") == 1);
  CHECK(std::count(names.begin(), names.end(), "ADMBase::gyy") == 0);  // = gxx, left out
  const hid_t file = H5Fopen((out / "data.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  double dx = 0, origin[3] = {0, 0, 0};
  const hid_t a = H5Aopen_by_name(file, "/grid", "dx", H5P_DEFAULT, H5P_DEFAULT);
  H5Aread(a, H5T_NATIVE_DOUBLE, &dx);
  H5Aclose(a);
  const hid_t o = H5Aopen_by_name(file, "/grid", "origin_xyz", H5P_DEFAULT, H5P_DEFAULT);
  H5Aread(o, H5T_NATIVE_DOUBLE, origin);
  H5Aclose(o);
  for (std::size_t c = 1; c < names.size(); ++c) {
    INFO(names[c]);
    const std::size_t sep = names[c].find("::");
    REQUIRE(sep != std::string::npos);
    std::string path(1, '/');
    path.append(names[c], 0, sep).append(1, '/').append(names[c], sep + 2, std::string::npos);
    hsize_t nx = 0;
    const std::vector<double> row = h5_row(file, path, nx);
    REQUIRE(rows.size() == nx);
    for (std::size_t i = 0; i < nx; ++i) {
      CHECK(rows[i][0] == Approx(origin[0] + dx * static_cast<double>(i)).margin(1e-12));
      CHECK(rows[i][c] == Approx(row[i]).epsilon(1e-14).margin(1e-300));
    }
  }
  H5Fclose(file);
}
