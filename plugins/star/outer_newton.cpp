#include "outer_newton.hpp"

#include <fmt/format.h>

#include <cmath>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::star {

namespace {

// Newton stops when a full step moves every unknown by less than this, relative. The sigma-model's
// values carry round-off (its TOV profile solve, ~1e-11), which the finite-difference dF/dsigma
// divides: for a weak-field star (rho_max = 0.01, the Kepler limit) dalpha/dsigma is small and
// 1e-12 was below that floor (measured: 50 steps without reaching it). 1e-10 is four orders below
// the outer tolerance.
constexpr double newton_step_tolerance = 1e-10;

struct Residuals {
  double f[3];
  double dfds[3];
  double dfdw[3];
  double dfdc[3];
};

/// F_P and its derivatives at (s, w, c) for every point; the model's change from sigma_old shifts
/// alpha and phi.
class Evaluator {
 public:
  Evaluator(const std::vector<AxisPoint>& points, const FieldModel& model, const PointResidual& residual, double sigma_old)
      : points_(points), model_(model), residual_(residual), at_old_(model(sigma_old)) {}

  Residuals operator()(double s, double w, double c) const {
    const double ds = 1e-6 * s;
    const ModelValues m = model_(s), mp = model_(s + ds), mm = model_(s - ds);
    Residuals r{};
    for (std::size_t p = 0; p < points_.size(); ++p) {
      const AxisPoint& q = points_[p];
      auto at = [&](const ModelValues& v) {
        return residual_(p, q.alpha + v.alpha[p] - at_old_.alpha[p], q.phi + v.phi[p] - at_old_.phi[p], w, c, q.enthalpy);
      };
      const AxisResidual here = at(m);
      r.f[p] = here.f;
      r.dfdw[p] = here.df_domega;
      r.dfdc[p] = here.df_dbernoulli;
      r.dfds[p] = (at(mp).f - at(mm).f) / (2 * ds);
    }
    return r;
  }

 private:
  const std::vector<AxisPoint>& points_;
  const FieldModel& model_;
  const PointResidual& residual_;
  ModelValues at_old_;
};

}  // namespace

NewtonResult solve_sigma_bernoulli(const std::vector<AxisPoint>& points, const FieldModel& model,
                                   const PointResidual& residual, double sigma_old, double omega_hat, double c_start) {
  if (points.size() != 2) throw core::RunFailure("star: the single star's Newton solve takes exactly two axis points");
  const Evaluator evaluate(points, model, residual, sigma_old);
  double s = sigma_old, c = c_start;
  Residuals r = evaluate(s, omega_hat, c);
  for (int it = 1; it <= 50; ++it) {
    // [dF0/ds  dF0/dc] [ds]   [-F0]
    // [dF1/ds  dF1/dc] [dc] = [-F1]
    const double det = r.dfds[0] * r.dfdc[1] - r.dfdc[0] * r.dfds[1];
    if (!(std::fabs(det) > 0) || !std::isfinite(det))
      throw core::RunFailure(fmt::format("star: the (sigma, C_B) Newton matrix is singular at sigma = {}, C_B = {}: the "
                                         "centre and surface lapses do not depend differently on sigma",
                                         s, c));
    const double ds = (-r.f[0] * r.dfdc[1] + r.dfdc[0] * r.f[1]) / det;
    const double dc = (-r.dfds[0] * r.f[1] + r.dfds[1] * r.f[0]) / det;
    double lambda = 1;
    for (int halving = 0;; ++halving) {
      try {
        const Residuals trial = evaluate(s + lambda * ds, omega_hat, c + lambda * dc);
        s += lambda * ds;
        c += lambda * dc;
        r = trial;
        break;
      } catch (const core::RunFailure& fold) {
        if (halving == 30) throw core::RunFailure(fmt::format("star: no sigma-model solution near sigma = {}: {}", s, fold.what()));
        lambda *= 0.5;
      }
    }
    if (!(c > 0)) throw core::RunFailure(fmt::format("star: the Newton solve gave C_B = {} <= 0 at sigma = {}", c, s));
    // Converged on a full step only: a step shrunk by the fold guard is small away from the root too.
    if (lambda == 1 && std::fabs(ds) <= newton_step_tolerance * std::fabs(s) && std::fabs(dc) <= newton_step_tolerance * c)
      return {s, omega_hat, c, it};
  }
  throw core::RunFailure(fmt::format("star: the (sigma, C_B) Newton solve did not converge in 50 iterations (last sigma "
                                     "= {}, C_B = {}, residuals {:.3e}, {:.3e})",
                                     s, c, r.f[0], r.f[1]));
}

NewtonResult solve_sigma_omega_bernoulli(const std::vector<AxisPoint>& points, const FieldModel& model,
                                         const PointResidual& residual, double sigma_old, double omega_start,
                                         double c_start) {
  if (points.size() != 3) throw core::RunFailure("star: the binary's Newton solve takes three axis points");
  if (!(omega_start > 0)) throw core::RunFailure(fmt::format("star: the Newton solve starts at Omegahat = {} <= 0", omega_start));
  const Evaluator evaluate(points, model, residual, sigma_old);
  double s = sigma_old, w = omega_start, c = c_start;
  Residuals r = evaluate(s, w, c);
  for (int it = 1; it <= 50; ++it) {
    // J dq = -F with J = [dF/ds, dF/dw, dF/dc] row by row; Cramer's rule on the 3 x 3 system.
    const double J[3][3] = {{r.dfds[0], r.dfdw[0], r.dfdc[0]}, {r.dfds[1], r.dfdw[1], r.dfdc[1]}, {r.dfds[2], r.dfdw[2], r.dfdc[2]}};
    auto det3 = [](const double m[3][3]) {
      return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
             m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double det = det3(J);
    if (!(std::fabs(det) > 0) || !std::isfinite(det))
      throw core::RunFailure(fmt::format("star: the (sigma, Omegahat, C_B) Newton matrix is singular at sigma = {}, "
                                         "Omegahat = {}, C_B = {}",
                                         s, w, c));
    double dq[3];
    for (int col = 0; col < 3; ++col) {
      double m[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] = j == col ? -r.f[i] : J[i][j];
      dq[col] = det3(m) / det;
    }
    double lambda = 1;
    for (int halving = 0;; ++halving) {
      const double ts = s + lambda * dq[0], tw = w + lambda * dq[1], tc = c + lambda * dq[2];
      bool accepted = false;
      if (tw > 0) {
        try {
          const Residuals trial = evaluate(ts, tw, tc);
          s = ts, w = tw, c = tc, r = trial;
          accepted = true;
        } catch (const core::RunFailure& fold) {
          if (halving == 30) throw core::RunFailure(fmt::format("star: no sigma-model solution near sigma = {}: {}", s, fold.what()));
        }
      }
      if (accepted) break;
      if (halving == 30)
        throw core::RunFailure(fmt::format("star: the Newton step leaves Omegahat > 0 only at a vanishing length (sigma = "
                                           "{}, Omegahat = {})",
                                           s, w));
      lambda *= 0.5;
    }
    if (!(c > 0)) throw core::RunFailure(fmt::format("star: the Newton solve gave C_B = {} <= 0 at sigma = {}", c, s));
    // Converged on a full step only: a step shrunk by a guard is small away from the root too.
    if (lambda == 1 && std::fabs(dq[0]) <= newton_step_tolerance * std::fabs(s) &&
        std::fabs(dq[1]) <= newton_step_tolerance * std::fabs(w) && std::fabs(dq[2]) <= newton_step_tolerance * c)
      return {s, w, c, it};
  }
  throw core::RunFailure(fmt::format("star: the (sigma, Omegahat, C_B) Newton solve did not converge in 50 iterations "
                                     "(last sigma = {}, Omegahat = {}, C_B = {})",
                                     s, w, c));
}

}  // namespace bhnsid::star
