#pragma once
// The 1/r coefficient of a field that tends to a constant, f = f_inf + B/r + O(1/r^2), read from
// the finest level the way the masses need it (M_ADM from phi, M_Komar from alpha). On a box whose
// faces lie at a few times the binary's size, the solid-angle average of r (f - f_inf) over one
// cube surface carries the O(1/r) terms (about 5 % of B on the paper's boxes), so the averages over
// every cube surface between half the box and its faces are fitted by B + C/s + D/s^2 (s the
// surface's half-width) and extrapolated to s -> infinity. Dipoles cancel in each average.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid {

struct FalloffFit {
  double coefficient = 0;  ///< B, extrapolated (hatted length units)
  double outermost = 0;    ///< the average r (f - f_inf) on the box's faces alone
  double slope = 0;        ///< C of the fit B + C/s + D/s^2
  int surfaces = 0;        ///< cube surfaces in the fit
};

/// The half-width (about the box's centre, max norm) of the smallest cube surface that encloses every
/// point where `density` > 0 (null: none) and the point `hole` (null: none), two spacings clear: the
/// 1/r expansion holds only outside every source.
inline double enclosing_half_width(const Level& lv, const double* density, const std::array<double, 3>* hole) {
  double extent = 0;
  if (hole) extent = std::max({std::fabs((*hole)[0]), std::fabs((*hole)[1]), std::fabs((*hole)[2])});
  if (density)
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j)
        for (int i = 0; i < lv.nx; ++i)
          if (density[lv.at(i, j, k)] > 0)
            extent = std::max({extent, std::fabs(lv.x(i)), std::fabs(lv.y(j)), std::fabs(lv.z(k))});
  return extent + 2 * lv.dx;
}

/// B of f = f_inf + B/r about `centre`, from the stored points of level `lv` (ghosts unread), over
/// the cube surfaces of half-width at least max(half the box, s_min); under equatorial symmetry the
/// stored half stands for the whole surface. Fewer than 4 such surfaces (a box that hardly clears
/// its sources): the coefficient is NaN, so that no one takes a fit through the matter for a mass.
inline FalloffFit falloff_fit(const Level& lv, const double* f, double f_inf, const std::array<double, 3>& centre,
                              double s_min = 0) {
  const int half = lv.n / 2, ic = half, kc = lv.z_symmetry ? 0 : half;
  std::vector<double> sum(static_cast<std::size_t>(half) + 1, 0.0), weight(sum.size(), 0.0);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const int off[3] = {std::abs(i - ic), std::abs(j - ic), std::abs(k - kc)};
        const int m = std::max({off[0], off[1], off[2]});
        if (2 * m < half || m * lv.dx < s_min) continue;
        const double d[3] = {lv.x(i) - centre[0], lv.y(j) - centre[1], lv.z(k) - centre[2]};
        const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        double w = 0;
        for (int a = 0; a < 3; ++a) {
          if (off[a] != m) continue;
          // Trapezoid area on this face: half on each edge it shares with another face, and half
          // on the symmetry plane for the side faces (their mirror half is not stored).
          double area = 1;
          for (int b = 0; b < 3; ++b)
            if (b != a && off[b] == m) area *= 0.5;
          if (lv.z_symmetry && a != 2 && k == 0) area *= 0.5;
          w += area * std::fabs(d[a]) / (r * r * r);
        }
        sum[static_cast<std::size_t>(m)] += w * r * (f[lv.at(i, j, k)] - f_inf);
        weight[static_cast<std::size_t>(m)] += w;
      }
  // Least squares A(s) = B + C u + D u^2, u = 1/s, over the surfaces (normal equations, Cramer).
  double m[3][3] = {}, rhs[3] = {};
  FalloffFit fit;
  for (int k = (half + 1) / 2; k <= half; ++k) {
    const auto q = static_cast<std::size_t>(k);
    if (!(weight[q] > 0) || k * lv.dx < s_min) continue;
    const double a = sum[q] / weight[q], u = 1.0 / (k * lv.dx), basis[3] = {1.0, u, u * u};
    for (int r = 0; r < 3; ++r) {
      rhs[r] += basis[r] * a;
      for (int c = 0; c < 3; ++c) m[r][c] += basis[r] * basis[c];
    }
    ++fit.surfaces;
    if (k == half) fit.outermost = a;
  }
  const auto det3 = [](const double (&a)[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double det = det3(m);
  if (fit.surfaces < 4 || !(std::fabs(det) > 0)) {
    fit.coefficient = std::numeric_limits<double>::quiet_NaN();
    return fit;
  }
  double solved[3];
  for (int c = 0; c < 3; ++c) {
    double mc[3][3];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) mc[r][k] = k == c ? rhs[r] : m[r][k];
    solved[c] = det3(mc) / det;
  }
  fit.coefficient = solved[0];
  fit.slope = solved[1];
  return fit;
}

}  // namespace bhnsid
