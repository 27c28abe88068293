// Lagrange interpolation on synthetic files: the order of the error, exactness at the points,
// mirroring by parity under equatorial symmetry, and the out-of-grid policies.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "reader_test.hpp"
#include "synth.hpp"

using reader_test::Points;
using reader_test::Random;
using reader_test::Reader;
using reader_test::work_path;

namespace {

double smooth(double x, double y, double z) { return std::sin(1.3 * x + 0.4) * std::cos(0.9 * y) * std::exp(0.5 * z) + 0.3 * x * y; }
double even_z(double x, double y, double z) { return std::cos(1.1 * z) * (1 + 0.4 * x - 0.2 * y * y) + 0.7 * z * z * x; }
double odd_z(double x, double y, double z) { return std::sin(1.2 * z) * (0.5 + x * y) + 0.3 * z * z * z; }

/// The cube [-0.8, 0.8]^3 sampled at spacing 1.6 / (n - 1).
std::string cube_file(const std::string& name, int n) {
  const std::string path = work_path(name);
  synth::Writer w(path);
  synth::GridSpec g;
  g.nx = g.ny = g.nz = n;
  g.dx = 1.6 / (n - 1);
  g.origin = {-0.8, -0.8, -0.8};
  w.header(g);
  w.dataset("/variables/f", {smooth});
  w.dataset("/variables/cubic", {[](double x, double y, double z) { return 1 + x - 2 * y * y * y + x * y * z + z * z * x; }});
  return path;
}

double max_error(const Reader& r, const Points& p, int order) {
  const std::vector<double> v = r.interpolate({"/variables/f"}, p, order)[0];
  double e = 0;
  for (std::size_t i = 0; i < p.size(); ++i) e = std::max(e, std::fabs(v[i] - smooth(p.x[i], p.y[i], p.z[i])));
  return e;
}

}  // namespace

TEST_CASE("reader.interpolation_error_falls_as_dx_to_the_order", "[reader]") {
  const Reader coarse(cube_file("order_coarse.h5", 17));  // dx = 0.1
  const Reader fine(cube_file("order_fine.h5", 33));      // dx = 0.05
  Random rnd(7);
  Points p;
  for (int i = 0; i < 400; ++i) p.add(rnd.uniform(-0.6, 0.6), rnd.uniform(-0.6, 0.6), rnd.uniform(-0.6, 0.6));
  // Points on the edges too: the shifted one-sided stencils keep the order.
  for (int i = 0; i < 50; ++i) p.add(rnd.uniform(-0.8, -0.75), rnd.uniform(0.75, 0.8), rnd.uniform(-0.8, 0.8));
  for (int order : {2, 4, 6, 8}) {
    const double ec = max_error(coarse, p, order), ef = max_error(fine, p, order);
    const double observed = std::log2(ec / ef);
    std::printf("order %d: max error %.3e (dx 0.1) %.3e (dx 0.05), observed order %.2f\n", order, ec, ef, observed);
    // Order 8 at dx = 0.1 is not yet asymptotic on the one-sided edge stencils (7.4 measured).
    CHECK(observed > order - (order >= 8 ? 0.8 : 0.35));
    CHECK(observed < order + 0.6);
  }
}

TEST_CASE("reader.interpolation_exact_at_points_and_for_polynomials", "[reader]") {
  const Reader r(cube_file("order_exact.h5", 17));
  Points nodes;
  for (int i : {0, 3, 16})
    for (int j : {0, 8, 16}) nodes.add(-0.8 + 0.1 * i, -0.8 + 0.1 * j, -0.8 + 0.1 * ((i + j) % 17));
  const std::vector<double> v = r.interpolate({"/variables/f"}, nodes)[0];
  for (std::size_t i = 0; i < nodes.size(); ++i)
    CHECK(v[i] == Approx(smooth(nodes.x[i], nodes.y[i], nodes.z[i])).epsilon(1e-14).margin(1e-15));
  // A polynomial of degree 3 per axis is reproduced by 4 points per axis, anywhere (edges included).
  Random rnd(3);
  Points p;
  for (int i = 0; i < 100; ++i) p.add(rnd.uniform(-0.8, 0.8), rnd.uniform(-0.8, 0.8), rnd.uniform(-0.8, 0.8));
  const std::vector<double> c = r.interpolate({"/variables/cubic"}, p, 4)[0];
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.x[i], y = p.y[i], z = p.z[i];
    REQUIRE(c[i] == Approx(1 + x - 2 * y * y * y + x * y * z + z * z * x).margin(1e-13));
  }
  // ... but not by 2 (the check can fail: linear interpolation misses the cubic terms).
  const std::vector<double> lin = r.interpolate({"/variables/cubic"}, p, 2)[0];
  double worst = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.x[i], y = p.y[i], z = p.z[i];
    worst = std::max(worst, std::fabs(lin[i] - (1 + x - 2 * y * y * y + x * y * z + z * z * x)));
  }
  CHECK(worst > 1e-4);
}

TEST_CASE("reader.equatorial_mirror_uses_parity", "[reader]") {
  // The same even and odd functions on a full grid and on its upper half with parity_z: the
  // stencils below z = 0 then see the same values, so both files give the same numbers.
  synth::GridSpec full;
  full.nx = full.ny = 13;
  full.nz = 13;
  full.dx = 0.1;
  full.origin = {-0.6, -0.6, -0.6};
  synth::GridSpec half = full;
  half.nz = 7;
  half.origin[2] = 0;
  half.equatorial = true;
  for (const auto& [name, g] : {std::pair{"mirror_full.h5", full}, std::pair{"mirror_half.h5", half}}) {
    synth::Writer w(work_path(name));
    w.header(g);
    w.dataset("/variables/even", {even_z, 1});
    w.dataset("/variables/odd", {odd_z, -1});
  }
  const Reader rf(work_path("mirror_full.h5")), rh(work_path("mirror_half.h5"));
  const bhnsid_reader_grid gh = rh.grid();
  CHECK(gh.equatorial == 1);
  CHECK(gh.lower[2] == Approx(-0.6));
  CHECK(gh.upper[2] == Approx(0.6));
  Random rnd(11);
  Points p;
  for (int i = 0; i < 200; ++i) p.add(rnd.uniform(-0.5, 0.5), rnd.uniform(-0.5, 0.5), rnd.uniform(-0.6, 0.6));
  for (double z : {-0.6, -0.25, -0.05, -1e-3, 0.0, 1e-3, 0.05}) p.add(0.13, -0.21, z);
  const auto vf = rf.interpolate({"/variables/even", "/variables/odd"}, p);
  const auto vh = rh.interpolate({"/variables/even", "/variables/odd"}, p);
  double even_err = 0, odd_err = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    REQUIRE(vh[0][i] == Approx(vf[0][i]).margin(1e-14));
    REQUIRE(vh[1][i] == Approx(vf[1][i]).margin(1e-14));
    even_err = std::max(even_err, std::fabs(vh[0][i] - even_z(p.x[i], p.y[i], p.z[i])));
    odd_err = std::max(odd_err, std::fabs(vh[1][i] - odd_z(p.x[i], p.y[i], p.z[i])));
  }
  CHECK(even_err < 1e-4);
  CHECK(odd_err < 1e-4);
  // f(x, y, -z) = parity f(x, y, z) at mirrored points.
  Points up, down;
  for (int i = 0; i < 50; ++i) {
    const double x = rnd.uniform(-0.5, 0.5), y = rnd.uniform(-0.5, 0.5), z = rnd.uniform(0, 0.6);
    up.add(x, y, z);
    down.add(x, y, -z);
  }
  const auto a = rh.interpolate({"/variables/even", "/variables/odd"}, up);
  const auto b = rh.interpolate({"/variables/even", "/variables/odd"}, down);
  for (std::size_t i = 0; i < up.size(); ++i) {
    REQUIRE(b[0][i] == Approx(a[0][i]).margin(1e-15));
    REQUIRE(b[1][i] == Approx(-a[1][i]).margin(1e-15));
  }
}

TEST_CASE("reader.out_of_grid_policies", "[reader]") {
  const std::string path = work_path("outside.h5");
  {
    synth::Writer w(path);
    synth::GridSpec g;
    g.nx = g.ny = g.nz = 9;
    g.dx = 0.25;
    g.origin = {-1, -1, -1};
    w.header(g);
    w.dataset("/variables/lin", {[](double x, double y, double z) { return 2 + x - 3 * y + 0.5 * z; }});
  }
  const Reader r(path);
  Points p;
  p.add(0.1, 0.2, 0.3);
  p.add(1.5, 0.2, -2.0);  // outside in x and z
  const reader_test::Result e = r.try_interpolate({"/variables/lin"}, p);
  CHECK(e.status == BHNSID_READER_ERR_OUTSIDE);
  CHECK_THAT(e.message, Catch::Contains("point 1") && Catch::Contains("outside the grid"));
  CHECK(e.values[0][0] == -12345.0);  // nothing written on an error
  // Clamp: the value at the nearest point of the box (1, 0.2, -1).
  const auto c = r.interpolate({"/variables/lin"}, p, 4, BHNSID_READER_OUTSIDE_CLAMP)[0];
  CHECK(c[1] == Approx(2 + 1 - 0.6 - 0.5).margin(1e-13));
  // Extrapolate: the edge polynomial continued; a linear field stays exact.
  const auto x = r.interpolate({"/variables/lin"}, p, 4, BHNSID_READER_OUTSIDE_EXTRAPOLATE)[0];
  CHECK(x[1] == Approx(2 + 1.5 - 0.6 - 1.0).margin(1e-12));
  CHECK(c[0] == Approx(2 + 0.1 - 0.6 + 0.15).margin(1e-13));
  // A point a round-off beyond the edge is inside.
  Points edge;
  edge.add(1.0 + 1e-14, -1.0 - 1e-14, 1.0);
  CHECK(r.try_interpolate({"/variables/lin"}, edge).status == BHNSID_READER_OK);
}
