#include "surface.hpp"

#include <cmath>
#include <numbers>

namespace bhnsid::horizon {

double real_harmonic(const Mode& mode, double theta, double phi) {
  const auto l = static_cast<unsigned>(mode.l), m = static_cast<unsigned>(std::abs(mode.m));
  // std::sph_legendre(l, m, theta) is Y_l^m(theta, 0), normalisation included.
  const double p = std::sph_legendre(l, m, theta);
  if (mode.m == 0) return p;
  return std::numbers::sqrt2 * p * (mode.m > 0 ? std::cos(m * phi) : std::sin(m * phi));
}

namespace {

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n from the Chebyshev guess).
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(static_cast<std::size_t>(n), 0.0);
  w.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 1;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double step = p1 / dp;
      z -= step;
      if (std::fabs(step) < 1e-16) break;
    }
    x[static_cast<std::size_t>(i)] = z;
    w[static_cast<std::size_t>(i)] = 2.0 / ((1 - z * z) * dp * dp);
  }
}

}  // namespace

SurfaceBasis::SurfaceBasis(int l_max, bool equatorial) : l_max_(l_max) {
  for (int l = 0; l <= l_max; ++l)
    for (int m = -l; m <= l; ++m)
      if (!equatorial || (l + std::abs(m)) % 2 == 0) modes_.push_back({l, m});
  // Twice the band limit in each direction: the products in the area and Theta stay resolved.
  const int n_theta = 2 * l_max + 4, n_phi = 4 * l_max + 8;
  std::vector<double> x, w;
  gauss_legendre(n_theta, x, w);
  for (int i = 0; i < n_theta; ++i) {
    if (equatorial && x[static_cast<std::size_t>(i)] < 0) continue;  // the mirror half: weights doubled
    const double weight = w[static_cast<std::size_t>(i)] * (equatorial ? 2.0 : 1.0) * 2 * std::numbers::pi / n_phi;
    for (int k = 0; k < n_phi; ++k)
      points_.push_back({std::acos(x[static_cast<std::size_t>(i)]), 2 * std::numbers::pi * k / n_phi, weight});
  }
}

double SurfaceBasis::radius(const std::vector<double>& a, double theta, double phi) const {
  double h = 0;
  for (std::size_t i = 0; i < modes_.size(); ++i) h += a[i] * real_harmonic(modes_[i], theta, phi);
  return h;
}

std::vector<double> SurfaceBasis::sphere(double r0) const {
  std::vector<double> a(modes_.size(), 0.0);
  a[0] = r0 * std::sqrt(4 * std::numbers::pi);  // Y_00 = 1/sqrt(4 pi)
  return a;
}

int SurfaceBasis::find(int l, int m) const {
  for (std::size_t i = 0; i < modes_.size(); ++i)
    if (modes_[i].l == l && modes_[i].m == m) return static_cast<int>(i);
  return -1;
}

}  // namespace bhnsid::horizon
