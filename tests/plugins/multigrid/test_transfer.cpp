// The multigrid plugin's own pieces, called directly on hand-built levels: the transfers
// reproduce what they must reproduce exactly, and the Robin rows are exact for a pure 1/r field up
// to the second-order interpolation error.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "boundary_rows.hpp"
#include "sweep_test_support.hpp"
#include "test_level.hpp"
#include "transfer.hpp"

using namespace bhnsid;
using namespace bhnsid::multigrid;

namespace {

using bhnsid::test::make_level;

template <class F>
std::vector<double> sample(const Level& lv, F f) {
  std::vector<double> v(lv.size, 0.0);
  for (int k = lv.z_symmetry ? -1 : 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) v[static_cast<std::size_t>(lv.at(i, j, k))] = f(lv.x(i), lv.y(j), lv.z(k));
  return v;
}

}  // namespace

TEST_CASE("plugins.multigrid.full_weighting_reproduces_linear_functions", "[plugins][multigrid]") {
  // Full weighting has weights summing to 1 and symmetric about the coarse point, so a linear
  // function is restricted to its own values at every coarse interior point; folding at Robin
  // faces changes exactly the points next to a face.
  for (bool sym : {false, true}) {
    const Level fine = make_level(16, 0.125, sym), coarse = make_level(8, 0.25, sym);
    auto f = [](double x, double y, double z) { return 1.5 + 0.3 * x - 0.7 * y + (0.2 + 0 * z); };
    const std::vector<double> u = sample(fine, f);
    std::vector<double> c(coarse.size, 0.0), folded(coarse.size, 0.0);
    restrict_full_weighting_minus(fine, coarse, u.data(), nullptr, c.data(), false);
    restrict_full_weighting_minus(fine, coarse, u.data(), nullptr, folded.data(), true);
    double worst = 0;
    int changed = 0, next_to_face = 0;
    for (int k = coarse.k_begin(); k < coarse.nz - 1; ++k)
      for (int j = 1; j < coarse.ny - 1; ++j)
        for (int i = 1; i < coarse.nx - 1; ++i) {
          const auto p = static_cast<std::size_t>(coarse.at(i, j, k));
          worst = std::max(worst, std::fabs(c[p] - f(coarse.x(i), coarse.y(j), coarse.z(k))));
          const bool near = i == 1 || i == coarse.nx - 2 || j == 1 || j == coarse.ny - 2 || k == coarse.nz - 2 ||
                            (k == 1 && !sym);
          next_to_face += near;
          changed += std::fabs(folded[p] - c[p]) > 1e-14;
          if (!near) CHECK(folded[p] == c[p]);
        }
    CHECK(worst < 1e-14);
    CHECK(changed == next_to_face);
  }
}

TEST_CASE("plugins.multigrid.prolongation_and_injection_are_exact_where_they_must_be", "[plugins][multigrid]") {
  // Trilinear interpolation is exact for a trilinear correction; injection copies coincident
  // points; held points and (without `faces`) face points receive nothing.
  const Level fine = make_level(16, 0.125, false), coarse = make_level(8, 0.25, false);
  auto e = [](double x, double y, double z) { return 0.5 + x * y - 2 * y * z + x * y * z; };
  const std::vector<double> c = sample(coarse, e), c_old(coarse.size, 0.0);
  std::vector<double> u(fine.size, 1.0);
  std::vector<std::uint8_t> held(fine.size, 0);
  held[static_cast<std::size_t>(fine.at(8, 8, 8))] = 1;
  prolong_correction(coarse, fine, c.data(), c_old.data(), u.data(), held.data(), false);
  double worst = 0;
  for (int k = 0; k < fine.nz; ++k)
    for (int j = 0; j < fine.ny; ++j)
      for (int i = 0; i < fine.nx; ++i) {
        const double got = u[static_cast<std::size_t>(fine.at(i, j, k))];
        if (fine.on_outer_face(i, j, k) || (i == 8 && j == 8 && k == 8))
          CHECK(got == 1.0);
        else
          worst = std::max(worst, std::fabs(got - 1.0 - e(fine.x(i), fine.y(j), fine.z(k))));
      }
  CHECK(worst < 1e-14);
  std::vector<double> back(coarse.size, 0.0);
  const std::vector<double> fine_e = sample(fine, e);
  restrict_injection(fine, coarse, fine_e.data(), back.data());
  for (int k = 0; k < coarse.nz; ++k)
    for (int j = 0; j < coarse.ny; ++j)
      for (int i = 0; i < coarse.nx; ++i)
        CHECK(back[static_cast<std::size_t>(coarse.at(i, j, k))] == Approx(e(coarse.x(i), coarse.y(j), coarse.z(k))).margin(1e-15));
}

TEST_CASE("plugins.multigrid.robin_rows_third_order_for_a_monopole", "[plugins][multigrid]") {
  // u = u_inf + 1/|x - x0| satisfies the Robin condition exactly; the discrete rows see only the
  // quadratic interpolation error, O(h^3), which the factor r/h of the rows turns into the O(h^2)
  // the solution needs: halving h on the same cube divides the largest row residual by 8 (+- 2:
  // the corners' rays cut cells differently at each resolution). Rows may lean on other face
  // points with weights summing to s < 1, so repeated relaxation from a perturbed state
  // satisfies every row exactly.
  const std::array<double, 3> x0{0.3, -0.1, 0.0};
  const double u_inf = 2.0;
  auto u = [&](double x, double y, double z) {
    return u_inf + 1.0 / std::sqrt((x - x0[0]) * (x - x0[0]) + (y - x0[1]) * (y - x0[1]) + (z - x0[2]) * (z - x0[2]));
  };
  double previous = 0;
  for (int n : {32, 64, 128}) {
    const Level lv = make_level(n, 4.0 / n, true);
    const RobinRows rows = robin_stencils(lv, x0, false);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      double sum = 0;
      for (std::size_t e = rows.begin[r]; e < rows.begin[r + 1]; ++e) sum += rows.weight[e];
      REQUIRE(sum == Approx(rows.scale[r]).margin(1e-14));
      REQUIRE(rows.scale[r] < 1.0);
    }
    std::vector<double> v = sample(lv, u), res(lv.size, 0.0);
    robin_residual(rows, u_inf, v.data(), nullptr, nullptr, res.data());
    double worst = 0;
    for (std::ptrdiff_t p : rows.point) worst = std::max(worst, std::fabs(res[static_cast<std::size_t>(p)]));
    INFO("n = " << n << ": largest row residual " << worst << ", previous " << previous);
    if (previous > 0) CHECK(previous / worst == Approx(8.0).margin(2.0));
    previous = worst;
    for (std::ptrdiff_t p : rows.point) v[static_cast<std::size_t>(p)] += 0.1;
    for (int pass = 0; pass < 30; ++pass) robin_relax(rows, u_inf, v.data(), nullptr, nullptr);
    robin_residual(rows, u_inf, v.data(), nullptr, nullptr, res.data());
    double after = 0;
    for (std::ptrdiff_t p : rows.point) after = std::max(after, std::fabs(res[static_cast<std::size_t>(p)]));
    CHECK(after <= 1e-12);
  }
}

TEST_CASE("plugins.multigrid.robin_rows_second_order_for_a_dipole", "[plugins][multigrid]") {
  // u = u_inf + X.d/|X|^3 (a dipole, ~ 1/r^2) does not satisfy the Robin condition (the condition
  // errs by O(1/r_c^2) at every h), so a row's residual divided by h is a discrete dv/dr that tends
  // to a non-zero limit; its own error is O(h^2) for the three-point rows and O(h) for the two-point
  // row (dv/dr imposed half a cell inside the face). The difference between n and 2n at one face
  // point removes the limit: it falls by 4 per halving of h for the three-point rows and by 2 for
  // the two-point row. This is what made chi and eta of a boosted puncture converge at first order.
  const std::array<double, 3> x0{0.0, 0.0, 0.0};
  const double u_inf = 1.0;
  auto u = [&](double x, double y, double z) {
    const double r2 = x * x + y * y + z * z;
    return u_inf + (0.7 * x - 0.4 * y + 0.2 * z) / (r2 * std::sqrt(r2));
  };
  // The residual at the face point (r_c, 0.5, 0.25) (a grid point at every n used, off every axis).
  auto face_residual = [&](int n, bool two_point) {
    const Level lv = make_level(n, 4.0 / n, false);
    const RobinRows rows = robin_stencils(lv, x0, two_point);
    std::vector<double> v = sample(lv, u), res(lv.size, 0.0);
    robin_residual(rows, u_inf, v.data(), nullptr, nullptr, res.data());
    const int i = n, j = static_cast<int>(std::lround((0.5 - lv.origin[1]) / lv.dx)),
              k = static_cast<int>(std::lround((0.25 - lv.origin[2]) / lv.dx));
    return res[static_cast<std::size_t>(lv.at(i, j, k))] / lv.dx;  // the row over h: a derivative
  };
  for (bool two_point : {false, true}) {
    double d[2];
    for (int q = 0; q < 2; ++q) {
      const int n = 32 << q;
      d[q] = face_residual(n, two_point) - face_residual(2 * n, two_point);
    }
    INFO((two_point ? "two-point" : "three-point") << " rows: differences " << d[0] << ", " << d[1]);
    CHECK(d[0] / d[1] == Approx(two_point ? 2.0 : 4.0).margin(0.5));
  }
}

TEST_CASE("plugins.multigrid.robin_rows_the_same_on_any_number_of_threads", "[plugins][multigrid]") {
  // The threads build contiguous runs of face rows and write them into arrays sized in a first
  // pass: the rows must be those of one thread, entry for entry, and a failure must be the first
  // face point in order, whichever thread meets it.
  const Level lv = make_level(32, 0.125, true);
  const std::array<double, 3> x0{0.3, -0.1, 0.0};
  const RobinRows one = [&] {
    const bhnsid::test::Threads serial(1);
    return robin_stencils(lv, x0, false);
  }();
  for (int threads : {2, 3, 5}) {
    const bhnsid::test::Threads scoped(threads);
    const RobinRows many = robin_stencils(lv, x0, false);
    INFO(threads << " threads");
    REQUIRE(many.size() == one.size());
    CHECK(std::equal(many.point.begin(), many.point.end(), one.point.begin()));
    CHECK(std::equal(many.begin.begin(), many.begin.end(), one.begin.begin()));
    CHECK(std::equal(many.scale.begin(), many.scale.end(), one.scale.begin()));
    REQUIRE(many.index.size() == one.index.size());
    CHECK(std::equal(many.index.begin(), many.index.end(), one.index.begin()));
    CHECK(std::equal(many.weight.begin(), many.weight.end(), one.weight.begin()));
  }
  // A centre 1.2 cells inside the face x = 2 at z = 1: the nine face points within one cell of its
  // foot fail, in the planes z = 0.875, 1, 1.125; on 3 threads the first thread's rows end within
  // them, so two threads fail, and the first point in order, (2, -0.125, 0.875), must be the one
  // reported.
  const std::array<double, 3> close{2.0 - 1.2 * 0.125, 0.0, 1.0};
  for (int threads : {1, 3}) {
    const bhnsid::test::Threads scoped(threads);
    INFO(threads << " threads");
    CHECK_THROWS_WITH(robin_stencils(lv, close, false), Catch::Contains("face point (2, -0.125, 0.875) on level 0"));
  }
  // On a coarse level the same nine points take the row about the centre moved out to 1.5 cells
  // along the normal: one plane one cell in, its weights summing to s_1 = 1 - 1 / 1.5.
  const RobinRows coarse = robin_stencils(lv, close, false, true);
  std::set<std::ptrdiff_t> near, plane_in;
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j) {
      plane_in.insert(lv.at(lv.nx - 2, j, k));
      if (std::fabs(lv.y(j)) < 0.13 && std::fabs(lv.z(k) - 1.0) < 0.13) near.insert(lv.at(lv.nx - 1, j, k));
    }
  int moved = 0;
  for (std::size_t r = 0; r < coarse.size(); ++r) {
    if (!near.count(coarse.point[r])) continue;
    ++moved;
    CHECK(coarse.scale[r] == Approx(1.0 / 3.0));
    for (std::size_t e = coarse.begin[r]; e < coarse.begin[r + 1]; ++e) CHECK(plane_in.count(coarse.index[e]) == 1);
  }
  CHECK(moved == 9);
}
