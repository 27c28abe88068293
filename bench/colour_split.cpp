#include "colour_split.hpp"

#include <omp.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "bhnsid/interfaces/vector_sweep.hpp"
#include "no_lower_term.hpp"
#include "test_level.hpp"
#include "timing.hpp"

namespace bhnsid::bench {

namespace {

/// Colour-split storage of one level (no symmetry, no ghosts): point (i, j, k) of colour
/// c = (i + j + k) % 2 at colour[c][(k ny + j) nh + i / 2]. In row (j, k) the points of colour c
/// are i = 2 h + q with q = (c + j + k) % 2, so their x neighbours (the other colour) sit at
/// h - 1 + q and h + q, their y and z neighbours (the other colour) and their (j +- 1, k +- 1)
/// diagonal neighbours (the same colour) at h, and their (i +- 1, j +- 1) and (i +- 1, k +- 1)
/// diagonal neighbours (the same colour) at h - 1 + q and h + q: unit stride in h throughout.
struct SplitLevel {
  int nx, ny, nz, nh;
  std::ptrdiff_t row(int j, int k) const {
    return (static_cast<std::ptrdiff_t>(k) * ny + j) * nh;
  }
};

/// One component's rows around row (j, k) for colour c's points: the other colour's (x, y, z
/// neighbours) and the same colour's (the mixed derivatives' diagonal neighbours), each aimed so
/// that point h reads [h].
struct SplitRows {
  const double *c, *l, *r, *ym, *yp, *zm, *zp;
  const double *ym_l, *ym_r, *yp_l, *yp_r, *zm_l, *zm_r, *zp_l, *zp_r, *ymzm, *ymzp, *ypzm, *ypzp;
};

SplitRows split_rows(const SplitLevel& s, const std::array<const double*, 2>& f, int c, int j, int k) {
  const int q = (c + j + k) & 1;
  const double *same = f[static_cast<std::size_t>(c)], *other = f[static_cast<std::size_t>(1 - c)];
  SplitRows w;
  w.c = same + s.row(j, k);
  w.l = other + s.row(j, k) + q - 1;
  w.r = other + s.row(j, k) + q;
  w.ym = other + s.row(j - 1, k), w.yp = other + s.row(j + 1, k);
  w.zm = other + s.row(j, k - 1), w.zp = other + s.row(j, k + 1);
  w.ym_l = same + s.row(j - 1, k) + q - 1, w.ym_r = same + s.row(j - 1, k) + q;
  w.yp_l = same + s.row(j + 1, k) + q - 1, w.yp_r = same + s.row(j + 1, k) + q;
  w.zm_l = same + s.row(j, k - 1) + q - 1, w.zm_r = same + s.row(j, k - 1) + q;
  w.zp_l = same + s.row(j, k + 1) + q - 1, w.zp_r = same + s.row(j, k + 1) + q;
  w.ymzm = same + s.row(j - 1, k - 1), w.ymzp = same + s.row(j - 1, k + 1);
  w.ypzm = same + s.row(j + 1, k - 1), w.ypzp = same + s.row(j + 1, k + 1);
  return w;
}

/// One red-black sweep of the principal part toward 0 on the split storage, in core's order
/// (colour 0 then 1; within a colour the odd planes from 1, then the even ones; rows in order) and
/// with core's arithmetic (stencil::principal), so that the values agree to the bit.
void split_sweep(const SplitLevel& s, std::array<std::array<double*, 2>, 3> v, double ih2, double factor) {
  constexpr double third = 1.0 / 3.0;
  for (int c = 0; c < 2; ++c)
    for (int pass = 0; pass < 2; ++pass) {
#pragma omp parallel for schedule(static)
      for (int k = 1 + pass; k < s.nz - 1; k += 2)
        for (int j = 1; j < s.ny - 1; ++j) {
          const int q = (c + j + k) & 1;
          std::array<SplitRows, 3> w;
          for (std::size_t a = 0; a < 3; ++a) w[a] = split_rows(s, {v[a][0], v[a][1]}, c, j, k);
          const SplitRows &x = w[0], &y = w[1], &z = w[2];
          double *vx = v[0][static_cast<std::size_t>(c)] + s.row(j, k), *vy = v[1][static_cast<std::size_t>(c)] + s.row(j, k),
                 *vz = v[2][static_cast<std::size_t>(c)] + s.row(j, k);
          const std::ptrdiff_t h0 = q == 0 ? 1 : 0, h1 = (s.nx - 2 - q) / 2;
#pragma omp simd
          for (std::ptrdiff_t h = h0; h <= h1; ++h) {
            auto lap = [h](const SplitRows& f) {
              return f.l[h] + f.r[h] + f.ym[h] + f.yp[h] + f.zm[h] + f.zp[h] - 6.0 * f.c[h];
            };
            auto dxx = [h](const SplitRows& f) { return f.l[h] + f.r[h] - 2.0 * f.c[h]; };
            auto dyy = [h](const SplitRows& f) { return f.ym[h] + f.yp[h] - 2.0 * f.c[h]; };
            auto dzz = [h](const SplitRows& f) { return f.zm[h] + f.zp[h] - 2.0 * f.c[h]; };
            auto dxy = [h](const SplitRows& f) { return 0.25 * (f.yp_r[h] - f.ym_r[h] - f.yp_l[h] + f.ym_l[h]); };
            auto dxz = [h](const SplitRows& f) { return 0.25 * (f.zp_r[h] - f.zm_r[h] - f.zp_l[h] + f.zm_l[h]); };
            auto dyz = [h](const SplitRows& f) { return 0.25 * (f.ypzp[h] - f.ypzm[h] - f.ymzp[h] + f.ymzm[h]); };
            const double lx = lap(x) + third * (dxx(x) + dxy(y) + dxz(z));
            const double ly = lap(y) + third * (dxy(x) + dyy(y) + dyz(z));
            const double lz = lap(z) + third * (dxz(x) + dyz(y) + dzz(z));
            const double none = 0.0;  // core's lower-order term, here absent
            vx[h] += factor * (ih2 * lx + none);
            vy[h] += factor * (ih2 * ly + none);
            vz[h] += factor * (ih2 * lz + none);
          }
        }
    }
}

}  // namespace

int colour_split_sweep(int n, int threads) {
  if (n < 32 || (n & (n - 1)) != 0) {
    std::cerr << "bhnsid-bench colour-split: --n must be a power of 2, at least 32, got " << n << "\n";
    return 2;
  }
  omp_set_num_threads(threads);
  const Level lv = test::make_level(n, 40.0 / n, false);
  const SplitLevel s{lv.nx, lv.ny, lv.nz, lv.nx / 2 + 1};
  const std::size_t split_size = static_cast<std::size_t>(s.nz) * s.ny * s.nh;
  std::vector<double> natural[3], split[3][2];
  for (int a = 0; a < 3; ++a) {
    natural[a].assign(lv.size, 0.0);
    split[a][0].assign(split_size, 0.0);
    split[a][1].assign(split_size, 0.0);
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j)
        for (int i = 0; i < lv.nx; ++i) {
          const double value = 0.01 * std::sin(0.37 * (i + 3 * j + 7 * k) + a);
          natural[a][static_cast<std::size_t>(lv.at(i, j, k))] = value;
          split[a][(i + j + k) & 1][static_cast<std::size_t>(s.row(j, k) + i / 2)] = value;
        }
  }
  const stencil::Components v{natural[0].data(), natural[1].data(), natural[2].data()};
  const std::array<std::array<double*, 2>, 3> w{{{split[0][0].data(), split[0][1].data()},
                                                 {split[1][0].data(), split[1][1].data()},
                                                 {split[2][0].data(), split[2][1].data()}}};
  const double omega = 1.15, ih2 = 1.0 / (lv.dx * lv.dx), factor = omega / ((20.0 / 3.0) * ih2);
  auto core_sweep = [&] { stencil::vector_relax_any(lv, v, nullptr, nullptr, omega, [] {}, NoLowerTerm{}); };
  auto split_sweep_once = [&] { split_sweep(s, w, ih2, factor); };
  // One sweep of each from the same values must agree point by point.
  core_sweep();
  split_sweep_once();
  double difference = 0;
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j)
        for (int i = 0; i < lv.nx; ++i)
          difference = std::max(difference, std::fabs(natural[a][static_cast<std::size_t>(lv.at(i, j, k))] -
                                                       split[a][(i + j + k) & 1][static_cast<std::size_t>(s.row(j, k) + i / 2)]));
  const double points = static_cast<double>(lv.nx - 2) * (lv.ny - 2) * (lv.nz - 2);
  const int reps = std::max(1, static_cast<int>(2e6 / points));
  const double core_seconds = best_seconds(reps, core_sweep), split_seconds = best_seconds(reps, split_sweep_once);
  const nlohmann::json out = {{"case", "colour_split_sweep"},
                              {"n", n},
                              {"threads", threads},
                              {"core_ns_per_point", core_seconds / points * 1e9},
                              {"colour_split_ns_per_point", split_seconds / points * 1e9},
                              {"ratio", split_seconds / core_seconds},
                              {"max_difference_after_one_sweep", difference}};
  std::cout << out.dump() << std::endl;
  return difference == 0.0 ? 0 : 1;
}

}  // namespace bhnsid::bench
