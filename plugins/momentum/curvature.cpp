#include "curvature.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "bhnsid/core/errors.hpp"
#include "kernels.hpp"

namespace bhnsid::momentum {

namespace {

/// The finest level's points that a coarser level's point (i, j, k) sees: every stride-th fine
/// point, the mirror image for k < 0 under equatorial symmetry.
struct Sample {
  const Level& fine;
  int stride;
  std::ptrdiff_t row(int j, int k) const { return fine.at(0, j * stride, (k < 0 ? -k : k) * stride); }
};

/// A first derivative along y or z on one row of a level as three taps into the finest level's
/// array, at offsets from the row's first sample: sum_t coef[t] f[row[t] + i stride]. Centred in the
/// interior and across z = 0 (the mirror image, its parity in the coefficient), one-sided second
/// order (-3 f0 + 4 f1 - f2)/(2h) on the outer faces.
struct Taps {
  std::ptrdiff_t row[3];
  double coef[3];
};

Taps taps(const Sample& s, const Level& lv, int j, int k, int axis, int parity_z, double inv_2h, std::ptrdiff_t base) {
  const int here = axis == 1 ? j : k, extent = axis == 1 ? lv.ny : lv.nz;
  const bool lower_face = !(axis == 2 && lv.z_symmetry);
  auto at = [&](int offset) { return (axis == 1 ? s.row(j + offset, k) : s.row(j, k + offset)) - base; };
  auto sign = [&](int offset) { return axis == 2 && k + offset < 0 ? static_cast<double>(parity_z) : 1.0; };
  if (here == 0 && lower_face) return {{at(0), at(1), at(2)}, {-3.0 * inv_2h, 4.0 * inv_2h, -inv_2h}};
  if (here == extent - 1) return {{at(0), at(-1), at(-2)}, {3.0 * inv_2h, -4.0 * inv_2h, inv_2h}};
  return {{at(1), at(-1), at(0)}, {inv_2h * sign(1), -inv_2h * sign(-1), 0.0}};
}

inline double tapped(const double* f, const Taps& t, std::ptrdiff_t i) {
  return t.coef[0] * f[t.row[0] + i] + t.coef[1] * f[t.row[1] + i] + t.coef[2] * f[t.row[2] + i];
}

/// One row of level l: W, chi and the ansatz weight q at the row's first sample in the finest level's arrays, the
/// taps of the y and z derivatives per component, the outputs at the row's first point.
struct CurvatureRow {
  const double *w0, *w1, *w2, *chi, *weight;
  Taps ty[3], tz[3];
  double *a0, *a1, *a2, *a3, *a4, *a5, *aa;
  double inv_2h;
  std::array<double, 3> x;  ///< coordinates of the row's first point
  double dx;
  std::array<double, 3> mom, x_bh;
  double* scratch;  ///< 2 nx doubles of the thread
};

/// Largest |Ahat_new - Ahat_old| and |Zhat| at a point or over a row.
struct PointChange {
  double change, zmax;
};

/// Ahat and aa at point i of the row (fi = i stride: its offset in the fine arrays), given the x
/// derivatives of W's three components. Scalars only, no branch: the row's loop must vectorise.
template <bool BowenYork>
[[gnu::always_inline]] inline PointChange curvature_point(const CurvatureRow& r, int i, std::ptrdiff_t fi, double dx0,
                                                          double dx1, double dx2) {
  const Sym6 lw = conformal_killing({dx0, tapped(r.w0, r.ty[0], fi), tapped(r.w0, r.tz[0], fi)},
                                    {dx1, tapped(r.w1, r.ty[1], fi), tapped(r.w1, r.tz[1], fi)},
                                    {dx2, tapped(r.w2, r.ty[2], fi), tapped(r.w2, r.tz[2], fi)});
  const double c0 = r.chi[fi], c2 = c0 * c0;
  const double factor = c2 * c2 * c2 * c0 / (2.0 * r.weight[fi]);  // chi^7 / (2 q)
  const std::array<double, 6> z = {factor * lw.xx, factor * lw.xy, factor * lw.xz,
                                   factor * lw.yy, factor * lw.yz, factor * lw.zz};
  std::array<double, 6> t = z;
  if constexpr (BowenYork) {
    const std::array<double, 6> b = bowen_york(r.mom, r.x_bh, {r.x[0] + r.dx * i, r.x[1], r.x[2]});
    t = {z[0] + b[0], z[1] + b[1], z[2] + b[2], z[3] + b[3], z[4] + b[4], z[5] + b[5]};
  }
  auto largest = [](double a, double b, double c, double d, double e, double f) {
    return std::max(std::max(std::max(a, b), std::max(c, d)), std::max(e, f));
  };
  const PointChange out{
      largest(std::fabs(t[0] - r.a0[i]), std::fabs(t[1] - r.a1[i]), std::fabs(t[2] - r.a2[i]),
              std::fabs(t[3] - r.a3[i]), std::fabs(t[4] - r.a4[i]), std::fabs(t[5] - r.a5[i])),
      largest(std::fabs(z[0]), std::fabs(z[1]), std::fabs(z[2]), std::fabs(z[3]), std::fabs(z[4]), std::fabs(z[5]))};
  r.a0[i] = t[0], r.a1[i] = t[1], r.a2[i] = t[2], r.a3[i] = t[3], r.a4[i] = t[4], r.a5[i] = t[5];
  r.aa[i] = squared_norm(t);
  return out;
}

/// Every point of the row: centred x derivatives inside, one-sided second order at i = 0, nx - 1.
template <bool BowenYork, class Stride>
PointChange curvature_row(const CurvatureRow& r, int nx, Stride st) {
  auto one_sided = [&](const double* f, int i, int dir) {
    const double* q = f + i * st;
    return dir * r.inv_2h * (-3.0 * q[0] + 4.0 * q[dir * st] - q[2 * dir * st]);
  };
  const PointChange first =
      curvature_point<BowenYork>(r, 0, 0, one_sided(r.w0, 0, 1), one_sided(r.w1, 0, 1), one_sided(r.w2, 0, 1));
  const PointChange last = curvature_point<BowenYork>(r, nx - 1, (nx - 1) * st, one_sided(r.w0, nx - 1, -1),
                                                      one_sided(r.w1, nx - 1, -1), one_sided(r.w2, nx - 1, -1));
  // The maxima go through the thread's scratch: with an omp simd max reduction GCC 12 kept the
  // scalar loop (the whole fill took 46 ms at n = 128; 22 ms now).
  double *point_change = r.scratch, *point_zmax = r.scratch + nx;
  const double h = r.inv_2h;
#pragma omp simd
  for (int i = 1; i < nx - 1; ++i) {
    const std::ptrdiff_t ip = (i + 1) * st, im = (i - 1) * st;
    const PointChange c = curvature_point<BowenYork>(r, i, i * st, h * (r.w0[ip] - r.w0[im]),
                                                     h * (r.w1[ip] - r.w1[im]), h * (r.w2[ip] - r.w2[im]));
    point_change[i] = c.change;
    point_zmax[i] = c.zmax;
  }
  PointChange row{std::max(first.change, last.change), std::max(first.zmax, last.zmax)};
  for (int i = 1; i < nx - 1; ++i) {
    row.change = std::max(row.change, point_change[i]);
    row.zmax = std::max(row.zmax, point_zmax[i]);
  }
  return row;
}

void check_off_the_points(const Grid& grid, const std::array<double, 3>& x_bh) {
  for (int l = 0; l < grid.num_levels(); ++l)
    if (!(grid.level(l).distance_to_nearest_point(x_bh) > 1e-6 * grid.level(l).dx))
      throw core::RunFailure(fmt::format("momentum: the puncture ({}, {}, {}) lies on a grid point of level {}, where "
                                         "the Bowen-York tensor is infinite",
                                         x_bh[0], x_bh[1], x_bh[2], l));
}

}  // namespace

CurvatureChange fill_curvature(Grid& grid, const CurvatureFields& fields, const Puncture* puncture) {
  const Level& fine = grid.finest();
  const double* w[3];
  int parity_z[3];
  for (int c = 0; c < 3; ++c) {
    w[c] = grid.data(fields.wvec, c, 0);
    parity_z[c] = grid.field_info(fields.wvec).parity[static_cast<std::size_t>(c)].z;
  }
  const double* chi = grid.data(fields.chi, 0, 0);
  const double* weight = grid.data(fields.weight, 0, 0);
  std::array<double, 3> mom{}, x_bh{};
  if (puncture) {
    mom = puncture->momentum();
    x_bh = puncture->position();
  }
  const bool bowen_york_term = mom[0] != 0 || mom[1] != 0 || mom[2] != 0;
  if (bowen_york_term) check_off_the_points(grid, x_bh);

  double max_change = 0, max_zhat = 0;
  for (int l = 0; l < grid.num_levels(); ++l) {
    const Level& lv = grid.level(l);
    const bool finest = l == 0;
    const Sample sample{fine, fine.n / lv.n};
    const std::ptrdiff_t st = sample.stride;
    const double inv_2h = 0.5 / lv.dx;
    double* a[6];
    for (int m = 0; m < 6; ++m) a[m] = grid.data(fields.ahat, m, l);
    double* aa = grid.data(fields.aa, 0, l);
#pragma omp parallel reduction(max : max_change, max_zhat)
    {
      std::vector<double> scratch(2 * static_cast<std::size_t>(lv.nx));
#pragma omp for schedule(static)
      for (int k = 0; k < lv.nz; ++k)
        for (int j = 0; j < lv.ny; ++j) {
          const std::ptrdiff_t row = sample.row(j, k), p = lv.at(0, j, k);
          CurvatureRow r{};
          r.w0 = w[0] + row, r.w1 = w[1] + row, r.w2 = w[2] + row, r.chi = chi + row, r.weight = weight + row;
          for (int c = 0; c < 3; ++c) {
            r.ty[c] = taps(sample, lv, j, k, 1, parity_z[c], inv_2h, row);
            r.tz[c] = taps(sample, lv, j, k, 2, parity_z[c], inv_2h, row);
          }
          r.a0 = a[0] + p, r.a1 = a[1] + p, r.a2 = a[2] + p, r.a3 = a[3] + p, r.a4 = a[4] + p, r.a5 = a[5] + p;
          r.aa = aa + p;
          r.inv_2h = inv_2h, r.x = {lv.x(0), lv.y(j), lv.z(k)}, r.dx = lv.dx, r.mom = mom, r.x_bh = x_bh;
          r.scratch = scratch.data();
          // The Bowen-York switch and the finest level's stride (1; 7/8 of the points) are
          // compile-time: a branch in the loop body, or a variable stride, kept GCC 12's loop scalar.
          auto fill = [&](auto by) {
            constexpr bool BY = decltype(by)::value;
            return st == 1 ? curvature_row<BY>(r, lv.nx, std::integral_constant<std::ptrdiff_t, 1>{})
                           : curvature_row<BY>(r, lv.nx, st);
          };
          const PointChange c = bowen_york_term ? fill(std::true_type{}) : fill(std::false_type{});
          if (finest) {
            max_change = std::max(max_change, c.change);
            max_zhat = std::max(max_zhat, c.zmax);
          }
        }
    }
    grid.fill_ghosts(fields.ahat, l);
    grid.fill_ghosts(fields.aa, l);
  }
  return {grid.global_max(max_change), grid.global_max(max_zhat)};
}

}  // namespace bhnsid::momentum
