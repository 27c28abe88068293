#include "outer_newton.hpp"

#include <fmt/format.h>

#include <cmath>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::hydro_corotating {

namespace {

struct Residual {
  double f[2];
  double dfds[2];
};

}  // namespace

NewtonResult solve_sigma_bernoulli(const std::vector<AxisPoint>& points, const AlphaModel& model, double sigma_old) {
  if (points.size() != 2) throw core::RunFailure("hydro_corotating: the static Newton solve takes exactly two axis points");
  const std::vector<double> at_old = model(sigma_old);
  auto alpha_of = [&](const std::vector<double>& m, int p) { return points[p].alpha + m[p] - at_old[p]; };
  // F_P = h_P^2 alpha_P(s)^2 - C^2 and dF_P/ds by a central difference of the model.
  auto evaluate = [&](double s, double c) {
    const double ds = 1e-6 * s;
    const std::vector<double> m = model(s), mp = model(s + ds), mm = model(s - ds);
    Residual r;
    for (int p = 0; p < 2; ++p) {
      const double h2 = points[p].enthalpy * points[p].enthalpy;
      const double a = alpha_of(m, p), ap = alpha_of(mp, p), am = alpha_of(mm, p);
      r.f[p] = h2 * a * a - c * c;
      r.dfds[p] = h2 * (ap * ap - am * am) / (2 * ds);
    }
    return r;
  };

  double s = sigma_old;
  // C_B from the surface point at the old sigma: the surface equation alone fixes it there.
  double c = points[1].enthalpy * points[1].alpha;
  Residual r = evaluate(s, c);
  for (int it = 1; it <= 50; ++it) {
    // [dF0/ds  -2c] [ds]   [-F0]
    // [dF1/ds  -2c] [dc] = [-F1]
    const double det = -2 * c * (r.dfds[0] - r.dfds[1]);
    if (!(std::fabs(det) > 0) || !std::isfinite(det))
      throw core::RunFailure(fmt::format("hydro_corotating: the (sigma, C_B) Newton matrix is singular at sigma = {}, "
                                         "C_B = {}: the centre and surface lapses do not depend differently on sigma",
                                         s, c));
    const double ds = (-r.f[0] * (-2 * c) - (-2 * c) * (-r.f[1])) / det;
    const double dc = (r.dfds[0] * (-r.f[1]) - r.dfds[1] * (-r.f[0])) / det;
    double lambda = 1;
    for (int halving = 0;; ++halving) {
      try {
        const Residual trial = evaluate(s + lambda * ds, c + lambda * dc);
        s += lambda * ds;
        c += lambda * dc;
        r = trial;
        break;
      } catch (const core::RunFailure& fold) {
        if (halving == 30)
          throw core::RunFailure(fmt::format("hydro_corotating: no sigma-model solution near sigma = {}: {}", s, fold.what()));
        lambda *= 0.5;
      }
    }
    if (!(c > 0))
      throw core::RunFailure(fmt::format("hydro_corotating: the Newton solve gave C_B = {} <= 0 at sigma = {}", c, s));
    if (std::fabs(lambda * ds) <= 1e-12 * std::fabs(s) && std::fabs(lambda * dc) <= 1e-12 * c)
      return {s, c, it};
  }
  throw core::RunFailure(fmt::format("hydro_corotating: the (sigma, C_B) Newton solve did not converge in 50 iterations "
                                     "(last sigma = {}, C_B = {}, residuals {:.3e}, {:.3e})",
                                     s, c, r.f[0], r.f[1]));
}

}  // namespace bhnsid::hydro_corotating
