// core's vector sweep (interfaces/vector_sweep.hpp), which the momentum and shift plugins run: on
// rough data, with and without held points and on a box, it must give the plain loop's result in
// the documented order (colour 0 then 1; within a colour the even planes, then the odd ones; rows
// and points in order), the same on any number of threads. Rows with held points take a different
// loop from rows without (with_row_mask), so a mask that reaches only some rows tests both.
#include <catch2/catch.hpp>

#include <omp.h>

#include <cmath>
#include <vector>

#include "bhnsid/interfaces/vector_sweep.hpp"
#include "test_level.hpp"
#include "sweep_test_support.hpp"

using namespace bhnsid;
using bhnsid::test::make_level;
using bhnsid::test::pattern;
using bhnsid::test::Threads;

namespace {

// z >= 0 storage: the ghost plane k = -1 holds plane 1, V^z odd.
void mirror(const Level& lv, std::vector<double>* v) {
  for (int c = 0; c < 3; ++c)
    for (int j = -1; j <= lv.ny; ++j)
      for (int i = -1; i <= lv.nx; ++i)
        v[c][static_cast<std::size_t>(lv.at(i, j, -1))] = (c == 2 ? -1.0 : 1.0) * v[c][static_cast<std::size_t>(lv.at(i, j, 1))];
}

// A lower-order term that reads first derivatives with a point-dependent coefficient, as the
// shift's does: N^a = a(idx) d_x V^a + b(idx) d_a V^y.
struct Lower {
  const double* a;
  const double* b;
  double inv_2h;
  std::ptrdiff_t sy, sz;
  stencil::Triple at(std::ptrdiff_t idx, std::ptrdiff_t i, const stencil::Rows& x, const stencil::Rows& y,
                     const stencil::Rows& z) const {
    const stencil::Triple gy = stencil::gradient(y, i, inv_2h);
    return {a[idx] * inv_2h * (x.c[i + 1] - x.c[i - 1]) + b[idx] * gy.x,
            a[idx] * inv_2h * (y.c[i + 1] - y.c[i - 1]) + b[idx] * gy.y,
            a[idx] * inv_2h * (z.c[i + 1] - z.c[i - 1]) + b[idx] * gy.z};
  }
};

// The same point update written out with plain indices, in the documented order.
void reference(const Level& lv, std::vector<double>* v, const std::vector<double>* rhs, const std::uint8_t* fixed,
               double omega, const Lower& lower, const stencil::Box& box) {
  const double ih2 = 1.0 / (lv.dx * lv.dx), factor = omega / ((20.0 / 3.0) * ih2);
  const std::ptrdiff_t sy = lv.sy, sz = lv.sz;
  for (int colour = 0; colour < 2; ++colour) {
    for (int pass = 0; pass < 2; ++pass)
      for (int k = box.k0 + pass; k <= box.k1; k += 2)
        for (int j = box.j0; j <= box.j1; ++j)
          for (int i = box.i0; i <= box.i1; ++i) {
            const std::ptrdiff_t p = lv.at(i, j, k);
            if (((i + j + k) & 1) != colour || (fixed && fixed[p])) continue;
            auto u = [&](int c, std::ptrdiff_t q) { return v[c][static_cast<std::size_t>(p + q)]; };
            double l[3];
            for (int c = 0; c < 3; ++c)
              l[c] = u(c, 1) + u(c, -1) + u(c, sy) + u(c, -sy) + u(c, sz) + u(c, -sz) - 6 * u(c, 0);
            // (1/3) d_a (d_b V^b): second derivatives and the 4-point mixed ones
            auto d2 = [&](int c, std::ptrdiff_t s) { return u(c, s) + u(c, -s) - 2 * u(c, 0); };
            auto mixed = [&](int c, std::ptrdiff_t s, std::ptrdiff_t t) {
              return 0.25 * (u(c, s + t) - u(c, s - t) - u(c, -s + t) + u(c, -s - t));
            };
            l[0] += (d2(0, 1) + mixed(1, 1, sy) + mixed(2, 1, sz)) / 3;
            l[1] += (mixed(0, 1, sy) + d2(1, sy) + mixed(2, sy, sz)) / 3;
            l[2] += (mixed(0, 1, sz) + mixed(1, sy, sz) + d2(2, sz)) / 3;
            const double h = lower.inv_2h, a = lower.a[p], b = lower.b[p];
            const double dy[3] = {h * (u(1, 1) - u(1, -1)), h * (u(1, sy) - u(1, -sy)), h * (u(1, sz) - u(1, -sz))};
            for (int c = 0; c < 3; ++c) {
              const double n = a * h * (u(c, 1) - u(c, -1)) + b * dy[c];
              const double r = ih2 * l[c] + n - (rhs ? rhs[c][static_cast<std::size_t>(p)] : 0.0);
              // The update of component c must not change what components c+1.. read: collect first.
              l[c] = r;
            }
            for (int c = 0; c < 3; ++c) v[c][static_cast<std::size_t>(p)] += factor * l[c];
          }
    if (colour == 0 && lv.z_symmetry && box.k0 == lv.k_begin()) mirror(lv, v);
  }
}

}  // namespace

TEST_CASE("core.vector_sweep.is_the_plain_red_black_sweep", "[core]") {
  // n = 16 runs every colour on one thread (below parallel_min_points); n = 32 in parallel, where
  // each thread's slab (2 to 16 planes) first relaxes its end planes and then runs its wavefront.
  for (const int n : {16, 32}) {
    INFO("n = " << n);
    const Level lv = make_level(n, 0.1, true);
    std::vector<double> a(lv.size), b(lv.size), v0[3], rhs[3];
    for (std::size_t idx = 0; idx < lv.size; ++idx) a[idx] = 3 * pattern(idx, 7), b[idx] = 2 * pattern(idx, 8);
    for (int c = 0; c < 3; ++c) {
      v0[c].resize(lv.size), rhs[c].resize(lv.size);
      for (std::size_t idx = 0; idx < lv.size; ++idx) v0[c][idx] = pattern(idx, c), rhs[c][idx] = 50 * pattern(idx, 3 + c);
    }
    mirror(lv, v0);
    // Held: a 3 x 3 x 2 block off the centre, so some rows hold points and most do not.
    std::vector<std::uint8_t> mask(lv.size, 0);
    const int q = n / 16;
    for (int k = 0; k <= 1; ++k)
      for (int j = 6 * q; j <= 6 * q + 2; ++j)
        for (int i = 9 * q; i <= 9 * q + 2; ++i) mask[static_cast<std::size_t>(lv.at(i, j, k))] = 1;
    const Lower lower{a.data(), b.data(), 0.5 / lv.dx, lv.sy, lv.sz};
    const stencil::Box whole = stencil::interior(lv), box{5 * q, 13 * q, 3 * q, 11 * q, 0, 4 * q + q / 2};
    for (const stencil::Box& region : {whole, box})
      for (const bool held : {false, true}) {
        const std::uint8_t* fixed = held ? mask.data() : nullptr;
        std::vector<double> expected[3] = {v0[0], v0[1], v0[2]};
        reference(lv, expected, rhs, fixed, 1.15, lower, region);
        std::vector<std::vector<double>> first;
        for (int threads : {1, 2, 3, 5}) {
          Threads t(threads);
          std::vector<double> v[3] = {v0[0], v0[1], v0[2]};
          const double* rhs_ptrs[3] = {rhs[0].data(), rhs[1].data(), rhs[2].data()};
          stencil::vector_relax_any(lv, {v[0].data(), v[1].data(), v[2].data()}, rhs_ptrs, fixed, 1.15,
                                    [&] { mirror(lv, v); }, lower, region);
          double diff = 0;
          for (int c = 0; c < 3; ++c)
            for (std::size_t idx = 0; idx < lv.size; ++idx)
              diff = std::max(diff, std::fabs(v[c][idx] - expected[c][idx]));
          INFO("box " << (region.i0 == whole.i0 ? "whole" : "part") << ", held " << held << ", threads " << threads);
          CHECK(diff <= 1e-12);
          if (held)
            for (int c = 0; c < 3; ++c)
              for (std::size_t idx = 0; idx < lv.size; ++idx)
                if (mask[idx]) REQUIRE(v[c][idx] == v0[c][idx]);
          if (first.empty())
            first = {v[0], v[1], v[2]};
          else
            for (int c = 0; c < 3; ++c) CHECK(v[c] == first[static_cast<std::size_t>(c)]);
        }
      }
  }
}
