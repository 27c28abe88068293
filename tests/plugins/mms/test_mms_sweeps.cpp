// The order of the Gauss-Seidel sweeps: the fused plane-by-plane scalar sweep
// (stencil::red_black_sweep) gives exactly the plain red-black result on any number of threads,
// the vector sweep (whose mixed derivatives couple points of one colour) gives the same bits on
// any number of threads, and the z >= 0 half cube with its mirror ghosts reproduces the full cube.
#include <catch2/catch.hpp>

#include <omp.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "kernels/laplace.hpp"
#include "kernels/vector_laplace.hpp"
#include "mms_test_support.hpp"
#include "sweep_test_support.hpp"

using namespace bhnsid;
using namespace bhnsid::mms;
using namespace bhnsid::mms::test;
using bhnsid::test::pattern;
using bhnsid::test::Threads;

namespace {

std::vector<double> filled(const Level& lv, int salt) {
  std::vector<double> v(lv.size);
  for (std::size_t idx = 0; idx < lv.size; ++idx) v[idx] = pattern(idx, salt);
  mirror_plane(lv, v.data(), 1.0);
  return v;
}

// Held points: a ball of radius 3 dx about the cube's centre line, as an excision would give.
std::vector<std::uint8_t> ball_mask(const Level& lv) {
  std::vector<std::uint8_t> m(lv.size, 0);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i)
        m[static_cast<std::size_t>(lv.at(i, j, k))] = std::hypot(lv.x(i), lv.y(j), lv.z(k)) <= 3 * lv.dx;
  return m;
}

// Plain red-black Gauss-Seidel, colour 0 everywhere, then the mirror, then colour 1.
void reference_sweep(const Level& lv, std::vector<double>& u, const std::vector<double>& s, const double* rhs,
                     const std::uint8_t* fixed, double omega) {
  const double h2 = lv.dx * lv.dx;
  for (int colour = 0; colour < 2; ++colour) {
    for (int k = lv.k_begin(); k < lv.nz - 1; ++k)
      for (int j = 1; j < lv.ny - 1; ++j)
        for (int i = 1; i < lv.nx - 1; ++i) {
          const std::size_t p = static_cast<std::size_t>(lv.at(i, j, k));
          if (((i + j + k) & 1) != colour || (fixed && fixed[p])) continue;
          const std::size_t sy = static_cast<std::size_t>(lv.sy), sz = static_cast<std::size_t>(lv.sz);
          const double sum = u[p - 1] + u[p + 1] + u[p - sy] + u[p + sy] + u[p - sz] + u[p + sz];
          const double f = s[p] - (rhs ? rhs[p] : 0.0);
          u[p] += omega * ((sum + h2 * f) / 6 - u[p]);
        }
    if (colour == 0) mirror_plane(lv, u.data(), 1.0);
  }
}

}  // namespace

TEST_CASE("plugins.mms.scalar_sweep_is_plain_red_black", "[plugins][mms]") {
  // laplace_relax on rough data, with and without rhs and held points, on the half cube (n = 32:
  // 16 planes, enough for the fused wavefront on up to 4 threads, the plain two-pass path on 8)
  // and the full cube (n = 16): the result is the plain red-black sweep's to 1e-14, and the
  // same bits on 1, 2, 4 and 8 threads.
  for (const bool z_symmetry : {true, false}) {
    const Level lv = make_level(z_symmetry ? 32 : 16, 0.1, z_symmetry);
    const std::vector<double> u0 = filled(lv, 0), s = filled(lv, 1), rhs = filled(lv, 2);
    const std::vector<std::uint8_t> mask = ball_mask(lv);
    for (const bool with_rhs_and_mask : {false, true}) {
      const double* r = with_rhs_and_mask ? rhs.data() : nullptr;
      const std::uint8_t* m = with_rhs_and_mask ? mask.data() : nullptr;
      std::vector<double> expected = u0;
      reference_sweep(lv, expected, s, r, m, 1.15);
      std::vector<std::vector<double>> results;
      for (int threads : {1, 2, 4, 8}) {
        Threads t(threads);
        std::vector<double> u = u0;
        kernels::laplace_relax(lv, u.data(), s.data(), r, m, 1.15, [&] { mirror_plane(lv, u.data(), 1.0); });
        double diff = 0;
        for (std::size_t idx = 0; idx < u.size(); ++idx) diff = std::max(diff, std::fabs(u[idx] - expected[idx]));
        INFO("z symmetry " << z_symmetry << ", rhs and mask " << with_rhs_and_mask << ", threads " << threads);
        CHECK(diff <= 1e-14);
        results.push_back(u);
      }
      for (const auto& u : results) CHECK(u == results[0]);
    }
  }
}

TEST_CASE("plugins.mms.vector_sweep_is_thread_independent", "[plugins][mms]") {
  // vector_relax (kappa = 0: the vectorised diagonal path; kappa = 2: the 3x3 solves), with rhs and
  // held points, gives the same bits on 1, 2, 3 and 8 threads: its Gauss-Seidel order within a
  // colour (even planes, then odd) does not depend on how planes are shared out.
  const Level lv = make_level(16, 0.1, true);
  std::vector<std::vector<double>> v0, s, rhs;
  for (int c = 0; c < 3; ++c) {
    v0.push_back(filled(lv, c));
    s.push_back(filled(lv, 3 + c));
    rhs.push_back(filled(lv, 6 + c));
  }
  const std::vector<std::uint8_t> mask = ball_mask(lv);
  const double* rhs_ptrs[3] = {rhs[0].data(), rhs[1].data(), rhs[2].data()};
  for (const double kappa : {0.0, 2.0}) {
    std::vector<std::vector<std::vector<double>>> results;
    for (int threads : {1, 2, 3, 8}) {
      Threads t(threads);
      auto v = v0;
      auto mirror = [&] {
        mirror_plane(lv, v[0].data(), 1.0);
        mirror_plane(lv, v[1].data(), 1.0);
        mirror_plane(lv, v[2].data(), -1.0);
      };
      kernels::vector_relax(lv, {v[0].data(), v[1].data(), v[2].data()}, {s[0].data(), s[1].data(), s[2].data()},
                            kappa, rhs_ptrs, mask.data(), 1.15, mirror);
      results.push_back(v);
    }
    for (const auto& v : results) CHECK(v == results[0]);
    CHECK(results[0] != v0);
  }
}

namespace {

// The unknowns of a problem relaxed on the half or the full cube (n = 8, r_c = 1) from the exact
// face values and u = 0 inside, `sweeps` sweeps with omega; returns the values at the points
// (i, j, k >= 0 in z) of the half cube, component by component.
std::vector<double> relaxed_upper_half(Problem problem, bool z_symmetry, int sweeps, double omega) {
  MemoryGrid grid(8, 0.25, z_symmetry);
  Manufactured m(grid, defaults(problem));
  m.set_exact();
  interior_to(grid, m.unknowns()[0], 0.0);
  RelaxArgs args;
  args.omega = omega;
  for (int s = 0; s < sweeps; ++s) sweep(equations_of(m), grid, args);
  const Level& lv = grid.finest();
  const int f = grid.field_id(m.unknowns()[0]);
  std::vector<double> out;
  for (int c = 0; c < m.exact().components(); ++c)
    for (int k = z_symmetry ? 0 : lv.n / 2; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j)
        for (int i = 0; i < lv.nx; ++i) out.push_back(grid.data(f, c, 0)[lv.at(i, j, k)]);
  return out;
}

}  // namespace

TEST_CASE("plugins.mms.half_cube_reproduces_full_cube", "[plugins][mms]") {
  // Equatorial symmetry through the mirror ghosts: one scalar sweep (ball problem; the colour
  // order makes a sweep independent of the point order) on the z >= 0 half cube equals the full
  // cube's on z >= 0 to 1e-14; the vector problem (V^z odd), converged with 200 over-relaxed
  // sweeps on both, agrees to 1e-12 (its order within a colour differs between the two).
  const auto half = relaxed_upper_half(Problem::ball, true, 1, 1.0);
  const auto full = relaxed_upper_half(Problem::ball, false, 1, 1.0);
  REQUIRE(half.size() == full.size());
  double diff = 0;
  for (std::size_t p = 0; p < half.size(); ++p) diff = std::max(diff, std::fabs(half[p] - full[p]));
  CHECK(diff <= 1e-14);

  const double omega = 2 / (1 + std::sin(std::numbers::pi / 8));
  const auto vhalf = relaxed_upper_half(Problem::vector, true, 200, omega);
  const auto vfull = relaxed_upper_half(Problem::vector, false, 200, omega);
  REQUIRE(vhalf.size() == vfull.size());
  double vdiff = 0, scale = 0;
  for (std::size_t p = 0; p < vhalf.size(); ++p) {
    vdiff = std::max(vdiff, std::fabs(vhalf[p] - vfull[p]));
    scale = std::max(scale, std::fabs(vfull[p]));
  }
  INFO("max |V_half - V_full| = " << vdiff << " of max |V| = " << scale);
  CHECK(vdiff <= 1e-12 * scale);
}
