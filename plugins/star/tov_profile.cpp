#include "tov_profile.hpp"

#include <algorithm>
#include <cmath>

namespace bhnsid::star {

namespace {

double lagrange4(const std::vector<double>& x, const std::vector<double>& y, std::size_t first, double at) {
  double sum = 0;
  for (std::size_t a = first; a < first + 4; ++a) {
    double w = 1;
    for (std::size_t b = first; b < first + 4; ++b)
      if (b != a) w *= (at - x[b]) / (x[a] - x[b]);
    sum += w * y[a];
  }
  return sum;
}

}  // namespace

TovPoint tov_at(const TovStar& star, double r_iso) {
  TovPoint p;
  const double r = std::fabs(r_iso);
  if (r >= star.radius_isotropic) {
    const double m = star.adm_mass / (2 * r);
    p.psi = 1 + m;
    p.alpha = (1 - m) / (1 + m);
    return p;
  }
  const std::vector<double>& x = star.r_iso;
  const std::size_t n = x.size();
  const std::size_t hi = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), r) - x.begin());
  const std::size_t first = std::min(n - 4, hi < 2 ? 0 : hi - 2);
  p.rho0 = std::max(0.0, lagrange4(x, star.rho0, first, r));
  p.psi = lagrange4(x, star.psi, first, r);
  p.alpha = lagrange4(x, star.alpha, first, r);
  return p;
}

}  // namespace bhnsid::star
