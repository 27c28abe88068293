#include "curvature.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "kernels.hpp"

namespace bhnsid::momentum {

namespace {

/// The finest level's values seen at the points of a coarser level (stride = 2^l fine intervals per
/// coarse one), with the mirror image below z = 0 under equatorial symmetry.
struct Sampler {
  const Level& fine;
  int stride;
  double value(const double* f, int parity_z, int i, int j, int k) const {
    if (k < 0) return parity_z * f[fine.at(i * stride, j * stride, -k * stride)];
    return f[fine.at(i * stride, j * stride, k * stride)];
  }
};

/// d f / d x_axis at point (i, j, k) of level lv: centred where both neighbours exist (below z = 0
/// through the mirror image), one-sided second order on the outer faces.
double derivative(const Sampler& s, const Level& lv, const double* f, int parity_z, int i, int j, int k, int axis,
                  double inv_2h) {
  int q[3] = {i, j, k};
  const int extent = axis == 0 ? lv.nx : axis == 1 ? lv.ny : lv.nz;
  const bool lower_face = !(axis == 2 && lv.z_symmetry);
  auto at = [&](int offset) {
    int p[3] = {q[0], q[1], q[2]};
    p[axis] += offset;
    return s.value(f, parity_z, p[0], p[1], p[2]);
  };
  const int here = q[axis];
  if (here == 0 && lower_face) return inv_2h * (-3.0 * at(0) + 4.0 * at(1) - at(2));
  if (here == extent - 1) return inv_2h * (3.0 * at(0) - 4.0 * at(-1) + at(-2));
  return inv_2h * (at(1) - at(-1));
}

void check_off_the_points(const Grid& grid, const std::array<double, 3>& x_bh) {
  for (int l = 0; l < grid.num_levels(); ++l) {
    const Level& lv = grid.level(l);
    const int extent[3] = {lv.nx, lv.ny, lv.nz};
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const double t = std::round((x_bh[static_cast<std::size_t>(a)] - lv.origin[static_cast<std::size_t>(a)]) / lv.dx);
      const double idx = std::fmin(std::fmax(t, 0.0), extent[a] - 1.0);
      const double d = x_bh[static_cast<std::size_t>(a)] - (lv.origin[static_cast<std::size_t>(a)] + idx * lv.dx);
      d2 += d * d;
    }
    if (!(std::sqrt(d2) > 1e-6 * lv.dx))
      throw core::RunFailure(fmt::format("momentum: the puncture ({}, {}, {}) lies on a grid point of level {}, where "
                                         "the Bowen-York tensor is infinite",
                                         x_bh[0], x_bh[1], x_bh[2], l));
  }
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
  const double* eta = grid.data(fields.eta, 0, 0);
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
    const Sampler sampler{fine, fine.n / lv.n};
    const double inv_2h = 0.5 / lv.dx;
    double* a[6];
    for (int m = 0; m < 6; ++m) a[m] = grid.data(fields.ahat, m, l);
    double* aa = grid.data(fields.aa, 0, l);
#pragma omp parallel for schedule(static) reduction(max : max_change, max_zhat)
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j)
        for (int i = 0; i < lv.nx; ++i) {
          stencil::Triple g[3];
          for (int c = 0; c < 3; ++c)
            g[c] = {derivative(sampler, lv, w[c], parity_z[c], i, j, k, 0, inv_2h),
                    derivative(sampler, lv, w[c], parity_z[c], i, j, k, 1, inv_2h),
                    derivative(sampler, lv, w[c], parity_z[c], i, j, k, 2, inv_2h)};
          const Sym6 s6 = conformal_killing(g[0], g[1], g[2]);
          const double lw[6] = {s6.xx, s6.xy, s6.xz, s6.yy, s6.yz, s6.zz};
          const double c0 = sampler.value(chi, 1, i, j, k), e0 = sampler.value(eta, 1, i, j, k);
          const double c2 = c0 * c0;
          const double factor = c2 * c2 * c2 * c0 / (2.0 * e0);  // chi^7 / (2 eta)
          std::array<double, 6> t{};
          if (bowen_york_term) t = bowen_york(mom, x_bh, {lv.x(i), lv.y(j), lv.z(k)});
          const std::ptrdiff_t p = lv.at(i, j, k);
          for (std::size_t m = 0; m < 6; ++m) {
            const double z = factor * lw[m];
            t[m] += z;
            if (finest) {
              max_zhat = std::fmax(max_zhat, std::fabs(z));
              max_change = std::fmax(max_change, std::fabs(t[m] - a[m][p]));
            }
            a[m][p] = t[m];
          }
          aa[p] = squared_norm(t);
        }
    grid.fill_ghosts(fields.ahat, l);
    grid.fill_ghosts(fields.aa, l);
  }
  return {grid.global_max(max_change), grid.global_max(max_zhat)};
}

}  // namespace bhnsid::momentum
