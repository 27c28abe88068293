// The reader on the solver's own data.h5 (the fixtures of tests/reader/CMakeLists.txt run it): it
// opens every run kind, lists fields and scalars, gives at grid points the stored datasets (read
// here with HDF5 directly; gxx and alp recomputed with the puncture's pole agree with the
// solver's to round-off), nothing non-finite at random points, and press and eps from rho by the
// stored EOS.
#include <catch2/catch.hpp>

#include <hdf5.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "reader_test.hpp"

using reader_test::Points;
using reader_test::Random;
using reader_test::Reader;

namespace {

std::string run_file(const std::string& name) { return std::string(READER_RUNS_DIR) + "/" + name + "/data.h5"; }

/// The dataset as stored, [k][j][i], independent of the reader; empty if absent.
std::vector<double> stored(const std::string& file, const std::string& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  std::vector<double> v;
  if (H5Lexists(f, path.c_str(), H5P_DEFAULT) > 0) {
    const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
    const hid_t s = H5Dget_space(d);
    v.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(s)));
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Sclose(s);
    H5Dclose(d);
  }
  H5Fclose(f);
  return v;
}

std::vector<std::string> names(const Reader& r, int (*count)(const bhnsid_reader*, size_t*),
                               int (*name)(const bhnsid_reader*, size_t, const char**)) {
  std::size_t n = 0;
  REQUIRE(count(r.get(), &n) == BHNSID_READER_OK);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n; ++i) {
    const char* s = nullptr;
    REQUIRE(name(r.get(), i, &s) == BHNSID_READER_OK);
    out.emplace_back(s);
  }
  return out;
}

std::string group_of(const std::string& field) {
  static const char* hydro[] = {"rho", "press", "eps", "vel[0]", "vel[1]", "vel[2]", "w_lorentz"};
  for (const char* h : hydro)
    if (field == h) return "/HydroBase/";
  return "/ADMBase/";
}

void check_run(const std::string& name, std::size_t expect_fields, bool puncture, bool star) {
  const std::string file = run_file(name);
  const Reader r(file);
  const char* status = nullptr;
  REQUIRE(bhnsid_reader_string_attribute(r.get(), "/", "status", &status) == BHNSID_READER_OK);
  CHECK(std::string(status) == "converged");
  const auto fields = names(r, bhnsid_reader_num_fields, bhnsid_reader_field_name);
  const auto scalars = names(r, bhnsid_reader_num_scalars, bhnsid_reader_scalar_name);
  CHECK(fields.size() == expect_fields);
  CHECK(scalars.size() > 5);
  CHECK(r.scalar("adm_mass") > 0);
  if (puncture) CHECK(r.scalar("bh_bare_mass") > 0);
  const bhnsid_reader_grid g = r.grid();

  // Every grid point of a few planes (z = 0, the one above, and a mirrored one).
  Points p;
  std::vector<std::size_t> flat;
  std::vector<int> mirrored;
  for (int k : {0, 1, -2})
    for (int j = 0; j < g.ny; j += 2)
      for (int i = 0; i < g.nx; ++i) {
        p.add(g.origin[0] + g.dx * i, g.origin[1] + g.dx * j, g.dx * k);
        flat.push_back((static_cast<std::size_t>(std::abs(k)) * g.ny + j) * g.nx + i);
        mirrored.push_back(k < 0);
      }
  const auto v = r.interpolate(fields, p);
  std::size_t compared = 0, held = 0;
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const std::string path = group_of(fields[f]) + fields[f];
    const std::vector<double> s = stored(file, path);
    double parity = 1;
    std::size_t one = 0;
    if (!s.empty())
      REQUIRE(bhnsid_reader_numeric_attribute(r.get(), path.c_str(), "parity_z", &parity, 1, &one) == BHNSID_READER_OK);
    const bool is_beta = fields[f].rfind("beta", 0) == 0;
    double centre[3] = {0, 0, 0}, half = -1;
    std::size_t count = 0;
    if (is_beta && !s.empty() &&
        bhnsid_reader_numeric_attribute(r.get(), path.c_str(), "held_region_half_size", &half, 1, &count) ==
            BHNSID_READER_OK)
      REQUIRE(bhnsid_reader_numeric_attribute(r.get(), path.c_str(), "held_region_centre", centre, 3, &count) ==
              BHNSID_READER_OK);
    for (std::size_t q = 0; q < p.size(); ++q) {
      const double got = v[f][q];
      REQUIRE(std::isfinite(got));
      // Absent means zero (the static star's beta and K_ij; a vacuum's matter), W = 1.
      const double want = s.empty() ? (fields[f] == "w_lorentz" ? 1.0 : 0.0) : (mirrored[q] ? parity : 1.0) * s[flat[q]];
      const bool in_cube = half >= 0 && std::fabs(p.x[q] - centre[0]) <= half + 1e-9 * g.dx &&
                           std::fabs(p.y[q] - centre[1]) <= half + 1e-9 * g.dx &&
                           std::fabs(p.z[q] - centre[2]) <= half + 1e-9 * g.dx;
      if (in_cube) {
        ++held;  // filled harmonically, not the held beta_0 (test_fields.cpp checks the fill)
        continue;
      }
      // gxx = phi^4 and alp = eta/phi: the solver summed M/2r on hatted coordinates, the reader on
      // physical ones (sigma M_hat / (2 sigma r_hat)), so a few ulps, amplified by the fourth power.
      INFO(name << " " << fields[f] << " at (" << p.x[q] << ", " << p.y[q] << ", " << p.z[q] << ")");
      REQUIRE(got == Approx(want).epsilon(1e-12).margin(1e-14));
      ++compared;
    }
  }
  std::printf("%s: %zu fields, %zu scalars; %zu values at grid points equal the stored ones, %zu in the excision "
              "cube filled\n", name.c_str(), fields.size(), scalars.size(), compared, held);
  CHECK((held > 0) == (name == "binary32" || name == "paper64" || name == "boosted" || name == "komar"));

  // Random points: finite everywhere, and the EOS's formulas on the returned rho.
  Random rnd(3);
  Points rp;
  for (int i = 0; i < 4000; ++i)
    rp.add(rnd.uniform(g.lower[0], g.upper[0]), rnd.uniform(g.lower[1], g.upper[1]), rnd.uniform(g.lower[2], g.upper[2]));
  if (star) {  // and around the star's centre (on the x axis), so that many points are in the star
    const double xc = r.scalar("star_center_x"), radius = 0.1 * (g.upper[0] - g.lower[0]);
    for (int i = 0; i < 1000; ++i)
      rp.add(xc + rnd.uniform(-radius, radius), rnd.uniform(-radius, radius), rnd.uniform(-radius, radius));
  }
  const auto w = r.interpolate(fields, rp);
  for (const auto& column : w)
    for (double x : column) REQUIRE(std::isfinite(x));
  if (!star) return;
  double k = 0, gamma = 0;
  std::size_t n = 0;
  REQUIRE(bhnsid_reader_numeric_attribute(r.get(), "/eos", "K", &k, 1, &n) == BHNSID_READER_OK);
  REQUIRE(bhnsid_reader_numeric_attribute(r.get(), "/eos", "Gamma", &gamma, 1, &n) == BHNSID_READER_OK);
  const auto fv = r.interpolate({"rho", "press", "eps", "w_lorentz"}, rp);
  std::size_t inside = 0;
  for (std::size_t q = 0; q < rp.size(); ++q) {
    const double rho = fv[0][q];
    REQUIRE(rho >= 0);
    inside += rho > 0;
    REQUIRE(fv[1][q] == Approx(k * std::pow(rho, gamma)).epsilon(1e-14).margin(0));
    REQUIRE(fv[2][q] == Approx(k * std::pow(rho, gamma - 1) / (gamma - 1)).epsilon(1e-14).margin(0));
    REQUIRE(fv[3][q] >= 1);
  }
  CHECK(inside > 100);
}

}  // namespace

TEST_CASE("reader.real.binary", "[reader]") { check_run("binary32", 23, true, true); }
TEST_CASE("reader.real.static_star", "[reader]") { check_run("static_star", 23, false, true); }
// A vacuum run: no HydroBase, so rho..w_lorentz are zero/one but still answered (absent = vacuum).
TEST_CASE("reader.real.boosted_puncture", "[reader]") { check_run("boosted", 23, true, false); }
// lapse_komar: alp = (eta~ - c M/(2r))/phi from /variables/eta_regular and /scalars@lapse_komar_c,
// negative inside the horizon; at the grid points it must equal the stored alp.
TEST_CASE("reader.real.komar_puncture", "[reader]") { check_run("komar", 23, true, false); }
// The paper's example (parfiles/paper_example.yaml) at its coarsest validation grid, n = 64.
TEST_CASE("reader.real.paper_example", "[reader]") {
  check_run("paper64", 23, true, true);
  const Reader r(run_file("paper64"));
  // Miller (2001)'s configuration: mu_bn = 3 (parfiles/paper_example.yaml); the hole is placed
  // from the star's mass one outer step before convergence, hence not to round-off.
  CHECK(r.scalar("bh_bare_mass") / r.scalar("ns_adm_mass") == Approx(3.0).epsilon(1e-4));
}
