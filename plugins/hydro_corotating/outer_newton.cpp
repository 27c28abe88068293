#include "outer_newton.hpp"

#include <fmt/format.h>

#include <cmath>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::hydro_corotating {

namespace {

// Newton stops when a full step moves every unknown by less than this, relative. The sigma-model's
// values carry round-off (its TOV profile solve, ~1e-11), which the finite-difference dF/dsigma
// divides: for a weak-field star (rho_max = 0.01, the Kepler limit) dalpha/dsigma is small and
// 1e-12 was below that floor (measured: 50 steps without reaching it). 1e-10 is four orders below
// the outer tolerance.
constexpr double newton_step_tolerance = 1e-10;

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
    // Converged on a full step only: a step shrunk by the fold guard is small away from the root too.
    if (lambda == 1 && std::fabs(ds) <= newton_step_tolerance * std::fabs(s) && std::fabs(dc) <= newton_step_tolerance * c)
      return {s, c, it};
  }
  throw core::RunFailure(fmt::format("hydro_corotating: the (sigma, C_B) Newton solve did not converge in 50 iterations "
                                     "(last sigma = {}, C_B = {}, residuals {:.3e}, {:.3e})",
                                     s, c, r.f[0], r.f[1]));
}

}  // namespace bhnsid::hydro_corotating

namespace bhnsid::hydro_corotating {

namespace {

struct OrbitResidual {
  double f[3];
  double dfds[3];
  double dfdw[3];
};

}  // namespace

OrbitResult solve_sigma_omega_bernoulli(const std::vector<OrbitPoint>& points, const FieldModel& model, double sigma_old,
                                        double omega_start, double c_start) {
  if (points.size() != 3) throw core::RunFailure("hydro_corotating: the corotating Newton solve takes three axis points");
  if (!(omega_start > 0)) throw core::RunFailure(fmt::format("hydro_corotating: the Newton solve starts at Omegahat = {} <= 0", omega_start));
  const ModelValues at_old = model(sigma_old);
  // F_P and its derivatives at (s, w, c); the model's change from sigma_old shifts alpha and phi.
  auto evaluate = [&](double s, double w, double c) {
    const double ds = 1e-6 * s;
    const ModelValues m = model(s), mp = model(s + ds), mm = model(s - ds);
    OrbitResidual r;
    for (std::size_t p = 0; p < 3; ++p) {
      const OrbitPoint& q = points[p];
      const double h2 = q.enthalpy * q.enthalpy;
      auto f_of = [&](const ModelValues& v, double ww) {
        const double a = q.alpha + v.alpha[p] - at_old.alpha[p], ph = q.phi + v.phi[p] - at_old.phi[p];
        const double u = q.beta_y + q.x * ww, ph2 = ph * ph;
        return h2 * (a * a - ph2 * ph2 * u * u);
      };
      const double ph = q.phi + m.phi[p] - at_old.phi[p], ph2 = ph * ph;
      r.f[p] = f_of(m, w) - c * c;
      r.dfds[p] = (f_of(mp, w) - f_of(mm, w)) / (2 * ds);
      r.dfdw[p] = -2.0 * h2 * ph2 * ph2 * (q.beta_y + q.x * w) * q.x;
    }
    return r;
  };
  double s = sigma_old, w = omega_start, c = c_start;
  OrbitResidual r = evaluate(s, w, c);
  for (int it = 1; it <= 50; ++it) {
    // J dq = -F with J = [dF/ds, dF/dw, -2c] row by row; Cramer's rule on the 3 x 3 system.
    const double J[3][3] = {{r.dfds[0], r.dfdw[0], -2 * c}, {r.dfds[1], r.dfdw[1], -2 * c}, {r.dfds[2], r.dfdw[2], -2 * c}};
    auto det3 = [](const double m[3][3]) {
      return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
             m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double det = det3(J);
    if (!(std::fabs(det) > 0) || !std::isfinite(det))
      throw core::RunFailure(fmt::format("hydro_corotating: the (sigma, Omegahat, C_B) Newton matrix is singular at "
                                         "sigma = {}, Omegahat = {}, C_B = {}",
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
          const OrbitResidual trial = evaluate(ts, tw, tc);
          s = ts, w = tw, c = tc, r = trial;
          accepted = true;
        } catch (const core::RunFailure& fold) {
          if (halving == 30)
            throw core::RunFailure(fmt::format("hydro_corotating: no sigma-model solution near sigma = {}: {}", s, fold.what()));
        }
      }
      if (accepted) break;
      if (halving == 30)
        throw core::RunFailure(fmt::format("hydro_corotating: the Newton step leaves Omegahat > 0 only at a vanishing "
                                           "length (sigma = {}, Omegahat = {})",
                                           s, w));
      lambda *= 0.5;
    }
    if (!(c > 0))
      throw core::RunFailure(fmt::format("hydro_corotating: the Newton solve gave C_B = {} <= 0 at sigma = {}", c, s));
    // Converged on a full step only: a step shrunk by a guard is small away from the root too.
    if (lambda == 1 && std::fabs(dq[0]) <= newton_step_tolerance * std::fabs(s) &&
        std::fabs(dq[1]) <= newton_step_tolerance * std::fabs(w) && std::fabs(dq[2]) <= newton_step_tolerance * c)
      return {s, w, c, it};
  }
  throw core::RunFailure(fmt::format("hydro_corotating: the (sigma, Omegahat, C_B) Newton solve did not converge in 50 "
                                     "iterations (last sigma = {}, Omegahat = {}, C_B = {})",
                                     s, w, c));
}

}  // namespace bhnsid::hydro_corotating
