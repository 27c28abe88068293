// Reading fields out of the grid (plugins/grid/grid_sampling.cpp): volume integrals, interpolation
// at arbitrary points and the x axis, measured against functions with known integrals and values.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "bhnsid/core/errors.hpp"
#include "hierarchy.hpp"
#include "uniform_grid.hpp"
#include <algorithm>
#include <tuple>

using namespace bhnsid;
using namespace bhnsid::grid;
using core::TensorKind;
using Catch::Matchers::Contains;



namespace {

std::unique_ptr<UniformGrid> make_grid(int n, double dx, Symmetry symmetry, int max_levels = 0) {
  HierarchySpec spec;
  spec.n = n;
  spec.dx = dx;
  spec.symmetry = symmetry;
  spec.max_levels = max_levels;
  return std::make_unique<UniformGrid>(build_hierarchy(spec), symmetry);
}

// Samples f at every stored point of one level into the array of component 0 of `field`.
template <class F>
double* sample(Grid& g, int field, int level, F f) {
  const Level& lv = g.level(level);
  double* v = g.data(field, 0, level);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) v[lv.at(i, j, k)] = f(lv.x(i), lv.y(j), lv.z(k));
  return v;
}

// exp(-(x^2 + 2 y^2 + 3 z^2)): smooth, not a polynomial, with derivatives that do not vanish at the
// faces of the cube, so neither the trapezoid rule nor the interpolation is exact for it.
double gauss(double x, double y, double z) { return std::exp(-(x * x + 2 * y * y + 3 * z * z)); }
// Odd in z, no symmetry in x.
double odd_gauss(double x, double y, double z) {
  return z * std::exp(-((x - 0.3) * (x - 0.3) + y * y + z * z));
}

// Integral of exp(-c t^2) over [-a, a]: sqrt(pi/c) erf(sqrt(c) a).
double gauss_1d(double c, double a) { return std::sqrt(M_PI / c) * std::erf(std::sqrt(c) * a); }

}  // namespace

TEST_CASE("plugins.grid.integrate_second_order", "[plugins][grid]") {
  // The trapezoid rule is second order: on the levels of one hierarchy (same cube of half-width
  // 1.5, dx = 3/16, 3/32, 3/64) the error of the integral of exp(-(x^2 + 2y^2 + 3z^2)) against the
  // exact product of erf's (gauss_1d) falls by 4 +- 0.4 per halving of dx (measured 3.98, 3.995;
  // errors -3.2e-3, -8.0e-4, -2.0e-4; the integrand is not small at the faces, so the rule is not
  // spectrally accurate here). The equatorial grid, which stores z >= 0 only, gives the full grid's
  // value to 1e-14 relative (measured 2e-16; the plane z = 0 counted once); a field odd in z
  // integrates to exactly 0 there.
  const double a = 1.5;
  const double exact = gauss_1d(1, a) * gauss_1d(2, a) * gauss_1d(3, a);
  std::array<std::vector<double>, 2> values;
  for (const Symmetry sym : {Symmetry::none, Symmetry::equatorial}) {
    auto grid = make_grid(64, 2 * a / 64, sym, 3);
    Grid& g = *grid;
    REQUIRE(g.num_levels() == 3);
    const int f = g.add_field("f", {TensorKind::scalar});
    for (int l = 0; l < 3; ++l)
      values[sym == Symmetry::equatorial].push_back(g.integrate(sample(g, f, l, gauss), Parity{}, l));
    if (sym == Symmetry::equatorial) {
      CHECK(g.integrate(sample(g, f, 0, odd_gauss), Parity{-1, 1}, 0) == 0.0);
      // The same stored values with even parity are not zero: the zero above comes from the parity.
      CHECK(std::fabs(g.integrate(g.data(f, 0, 0), Parity{1, 1}, 0)) > 0.1);
    } else {
      // On the full grid the odd field cancels only to round-off.
      CHECK(std::fabs(g.integrate(sample(g, f, 0, odd_gauss), Parity{-1, 1}, 0)) < 1e-14);
    }
  }
  const std::vector<double>& full = values[0];
  const std::vector<double>& half = values[1];
  const double e0 = full[0] - exact, e1 = full[1] - exact, e2 = full[2] - exact;
  INFO("exact " << exact << "; errors " << e2 << ", " << e1 << ", " << e0 << "; ratios " << e2 / e1 << ", " << e1 / e0);
  CHECK(e2 / e1 == Approx(4.0).margin(0.4));
  CHECK(e1 / e0 == Approx(4.0).margin(0.4));
  for (int l = 0; l < 3; ++l) CHECK(half[l] == Approx(full[l]).epsilon(1e-14));
}

namespace {

// Probe points of one level. `spread`: fixed in space, drawn by a deterministic generator over the
// whole cube. `plane` and `face`: at fixed offsets, in units of this level's dx, from points of the
// coarsest level (which every level shares), so that each probe sits at the same place within its
// stencil on every level and the error ratio measures the order rather than where the probe fell:
// `plane` within 1.3 dx of z = 0 on both sides (images on the equatorial grid), `face` within
// 1.4 dx of the faces, edges and corners (one-sided stencils).
struct Probes {
  std::vector<std::array<double, 3>> spread, plane, face;
};

Probes probes(const Level& lv, double coarsest_dx) {
  Probes p;
  unsigned state = 12345;
  auto uniform = [&] {  // in [-1, 1)
    state = state * 1103515245u + 12345u;
    return 2 * (((state >> 8) & 0xffffff) / double(0x1000000)) - 1;
  };
  const double a = lv.half_width(), d = lv.dx, c = coarsest_dx;
  for (int q = 0; q < 200; ++q) p.spread.push_back({a * uniform(), a * uniform(), a * uniform()});
  const double plane_offsets[] = {0.31, -0.47, 0.83, -1.29, 0.05};
  for (int q = 0; q < 5; ++q) {
    const double theta = plane_offsets[q];
    p.plane.push_back({(q % 3 - 1) * c + 0.37 * d, (1 - q % 3) * c - 0.58 * d, theta * d});
    p.plane.push_back({((q + 1) % 3 - 1) * c - 0.21 * d, (q % 2) * c + 0.44 * d, theta * d});
  }
  const double face_offsets[] = {0.23, 0.71, 1.37};
  for (const double theta : face_offsets)
    for (const int s : {-1, 1}) {
      const double near = s * (a - theta * d);
      p.face.push_back({near, c + 0.4 * d, -c + 0.65 * d});
      p.face.push_back({-c - 0.35 * d, near, 0.52 * d});
      p.face.push_back({0.29 * d, c - 0.61 * d, near});
      p.face.push_back({near, -near, -c + 0.45 * d});
      p.face.push_back({near, near, near});
    }
  return p;
}

using Fn = double (*)(double, double, double);

// Largest, or root-mean-square, interpolation error over a set of probes.
double max_error(const Grid& g, const double* v, Parity parity, int level, const std::vector<std::array<double, 3>>& pts,
                 Fn f) {
  double m = 0;
  for (const auto& x : pts) m = std::max(m, std::fabs(g.interpolate(v, parity, level, x) - f(x[0], x[1], x[2])));
  return m;
}
double rms_error(const Grid& g, const double* v, Parity parity, int level, const std::vector<std::array<double, 3>>& pts,
                 Fn f) {
  double s = 0;
  for (const auto& x : pts) s += std::pow(g.interpolate(v, parity, level, x) - f(x[0], x[1], x[2]), 2);
  return std::sqrt(s / static_cast<double>(pts.size()));
}

// Cubic in every variable: tricubic interpolation reproduces it to round-off. Even and odd in z.
double cubic_even(double x, double y, double z) {
  return (1 + x - 0.5 * x * x + 0.3 * x * x * x) * (2 - y + 0.2 * y * y * y) * (1 + 0.7 * z * z);
}
double cubic_odd(double x, double y, double z) {
  return (0.5 - x + 0.25 * x * x * x) * (1 + 0.6 * y * y) * (z - 0.4 * z * z * z);
}

}  // namespace

TEST_CASE("plugins.grid.interpolate_fourth_order", "[plugins][grid]") {
  // Tricubic Lagrange interpolation errs by O(dx^4): on the levels of one hierarchy (cube half-width
  // 1.5, dx = 3/128, 3/64, 3/32) the error at the probes (see Probes; root mean square for the
  // spread, largest for the others) falls by 16 per halving of dx, for exp(-(x^2 + 2y^2 + 3z^2))
  // (parity +1) and z exp(-((x-0.3)^2 + y^2 + z^2)) (parity -1), in the interior, next to the plane
  // z = 0 (mirror images with the parity on the equatorial grid) and next to the faces (one-sided
  // stencils). Measured: 15.4 .. 18.1 (the faces' coarse pair is the largest); n = 64 (dx up to
  // 3/16) is not yet asymptotic (ratios 12.6 .. 20.2), hence n = 128. The band 16 +- 4 rejects third
  // order (8) and fifth (32). One exception, by design: next to the plane the odd field itself is
  // z = theta dx small, so its dx^4 error terms carry one more factor dx and fall by 32 (measured
  // 31.0, 31.4; band 32 +- 4). The equatorial grid gives the full grid's values to round-off (2e-16
  // measured): same stencils, and the images equal the lower half.
  const double a = 1.5;
  std::vector<std::vector<double>> results[2];
  for (const Symmetry sym : {Symmetry::none, Symmetry::equatorial}) {
    auto grid = make_grid(128, 2 * a / 128, sym, 3);
    Grid& g = *grid;
    REQUIRE(g.num_levels() == 3);
    const int even = g.add_field("even", {TensorKind::scalar});
    const int odd = g.add_field("odd", {TensorKind::vector_z});
    for (const auto& [field, fn, name] : {std::tuple{even, Fn{&gauss}, "even"}, std::tuple{odd, Fn{&odd_gauss}, "odd"}}) {
      const Parity parity = g.field_info(field).parity[0];
      double e[3][3];  // [set][level]
      for (int l = 0; l < 3; ++l) {
        const double* v = sample(g, field, l, fn);
        const Probes p = probes(g.level(l), g.coarsest().dx);
        e[0][l] = rms_error(g, v, parity, l, p.spread, fn);
        e[1][l] = max_error(g, v, parity, l, p.plane, fn);
        e[2][l] = max_error(g, v, parity, l, p.face, fn);
        std::vector<double> values;
        for (const auto* set : {&p.spread, &p.plane, &p.face})
          for (const auto& x : *set) values.push_back(g.interpolate(v, parity, l, x));
        results[sym == Symmetry::equatorial].push_back(values);
      }
      const char* sets[] = {"spread", "plane", "face"};
      for (int s = 0; s < 3; ++s) {
        const double r1 = e[s][1] / e[s][0], r2 = e[s][2] / e[s][1];
        INFO(name << (sym == Symmetry::equatorial ? ", equatorial, " : ", no symmetry, ") << sets[s] << ": errors "
                  << e[s][2] << ", " << e[s][1] << ", " << e[s][0] << "; ratios " << r2 << ", " << r1);
        const double expected = (s == 1 && parity.z < 0) ? 32 : 16;
        CHECK(r1 == Approx(expected).margin(4));
        CHECK(r2 == Approx(expected).margin(4));
        CHECK(e[s][0] < 2e-6);  // measured at most 1.2e-6 (even field, plane probes)
      }
    }
  }
  REQUIRE(results[0].size() == results[1].size());
  double worst = 0;
  for (std::size_t r = 0; r < results[0].size(); ++r)
    for (std::size_t q = 0; q < results[0][r].size(); ++q)
      worst = std::max(worst, std::fabs(results[0][r][q] - results[1][r][q]));
  CHECK(worst < 1e-14);
}

TEST_CASE("plugins.grid.interpolate_reproduces_cubics", "[plugins][grid]") {
  // Four-point Lagrange interpolation is exact for cubics, one-sided stencils and mirror images
  // included, so a function cubic in each variable comes back to round-off (1e-13 relative) at every
  // probe, on both grids and every level: with parity +1 for one even in z, with parity -1 for one
  // odd in z. Giving the odd one parity +1 on the equatorial grid instead must spoil the points
  // whose stencil reaches below z = 0, which shows the parity is applied. At grid points the stored
  // value comes back; a point outside the cube (or NaN) is a RunFailure.
  for (const Symmetry sym : {Symmetry::none, Symmetry::equatorial}) {
    INFO((sym == Symmetry::equatorial ? "equatorial" : "no symmetry"));
    auto grid = make_grid(16, 0.125, sym);
    Grid& g = *grid;
    REQUIRE(g.num_levels() == 3);  // 16, 8, 4: the coarsest has 5 points per axis (3 above z = 0)
    const int even = g.add_field("even", {TensorKind::scalar});
    const int odd = g.add_field("odd", {TensorKind::vector_z});
    for (int l = 0; l < g.num_levels(); ++l) {
      INFO("level " << l);
      const Level& lv = g.level(l);
      const double* ve = sample(g, even, l, cubic_even);
      const double* vo = sample(g, odd, l, cubic_odd);
      const Probes p = probes(lv, g.coarsest().dx);
      double worst_even = 0, worst_odd = 0, wrong_parity = 0;
      for (const auto* set : {&p.spread, &p.plane, &p.face})
        for (const auto& x : *set) {
          worst_even = std::max(worst_even, std::fabs(g.interpolate(ve, Parity{1, 1}, l, x) -
                                                      cubic_even(x[0], x[1], x[2])));
          worst_odd = std::max(worst_odd, std::fabs(g.interpolate(vo, Parity{-1, 1}, l, x) -
                                                    cubic_odd(x[0], x[1], x[2])));
          wrong_parity = std::max(wrong_parity, std::fabs(g.interpolate(vo, Parity{1, 1}, l, x) -
                                                          cubic_odd(x[0], x[1], x[2])));
        }
      CHECK(worst_even < 1e-13 * 10);  // |cubic_even| <= ~10 on the cube
      CHECK(worst_odd < 1e-13 * 5);
      if (lv.z_symmetry) CHECK(wrong_parity > 1e-3);
      else CHECK(wrong_parity < 1e-13 * 5);
      // Grid points, corners and the centre included.
      double at_nodes = 0;
      for (const int i : {0, 1, lv.nx / 2, lv.nx - 1})
        for (const int k : {0, 1, lv.nz - 1}) {
          const std::array<double, 3> x{lv.x(i), lv.y(lv.ny - 1 - i), lv.z(k)};
          at_nodes = std::max(at_nodes, std::fabs(g.interpolate(ve, Parity{}, l, x) - ve[lv.at(i, lv.ny - 1 - i, k)]));
        }
      CHECK(at_nodes < 1e-13);
    }
    const double a = g.finest().half_width();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double* v = g.data(even, 0, 0);
    for (const std::array<double, 3> x : {std::array<double, 3>{1.001 * a, 0, 0}, {0, -1.001 * a, 0}, {0, 0, -1.001 * a},
                                          {0, 0, 1.001 * a}, {nan, 0, 0}, {0, 0, nan}})
      CHECK_THROWS_AS(g.interpolate(v, Parity{}, 0, x), core::RunFailure);
    CHECK_THROWS_WITH(g.interpolate(v, Parity{}, 0, {0, 0, -1.001 * a}), Contains("outside the cube"));
    CHECK_NOTHROW(g.interpolate(v, Parity{}, 0, {a, -a, -a}));
  }
}

TEST_CASE("plugins.grid.line_x_is_the_x_axis", "[plugins][grid]") {
  // line_x returns the nx stored values with j = n/2 (y = 0) and k = n/2 (full grid) or k = 0
  // (equatorial grid: z = 0 is the bottom plane), paired with x_i = -n dx/2 + i dx, on every level.
  // Values are index-coded (i + 1000 j + 10^6 k) so a wrong row or plane cannot pass. A level with
  // an odd number of intervals (n = 5 below 160 = 5 x 2^5) has no axis line: RunFailure.
  for (const Symmetry sym : {Symmetry::none, Symmetry::equatorial}) {
    auto grid = make_grid(16, 0.25, sym);
    Grid& g = *grid;
    const int f = g.add_field("f", {TensorKind::scalar});
    for (int l = 0; l < g.num_levels(); ++l) {
      const Level& lv = g.level(l);
      double* v = g.data(f, 0, l);
      for (int k = 0; k < lv.nz; ++k)
        for (int j = 0; j < lv.ny; ++j)
          for (int i = 0; i < lv.nx; ++i) v[lv.at(i, j, k)] = i + 1000.0 * j + 1e6 * k;
      const auto line = g.line_x(v, l);
      REQUIRE(line.size() == static_cast<std::size_t>(lv.nx));
      const int k_axis = sym == Symmetry::equatorial ? 0 : lv.n / 2;
      int wrong = 0;
      for (int i = 0; i < lv.nx; ++i) {
        wrong += line[static_cast<std::size_t>(i)][0] != -lv.half_width() + i * lv.dx;
        wrong += line[static_cast<std::size_t>(i)][1] != i + 1000.0 * (lv.n / 2) + 1e6 * k_axis;
      }
      INFO("level " << l);
      CHECK(wrong == 0);
    }
  }
  HierarchySpec spec;
  spec.n = 20;
  spec.dx = 0.1;
  auto odd = std::make_unique<UniformGrid>(build_hierarchy(spec), Symmetry::none);
  Grid& g = *odd;
  REQUIRE(g.coarsest().n == 5);
  const int f = g.add_field("f", {TensorKind::scalar});
  CHECK_NOTHROW(g.line_x(g.data(f, 0, 1), 1));
  CHECK_THROWS_AS(g.line_x(g.data(f, 0, 2), 2), core::RunFailure);
}
