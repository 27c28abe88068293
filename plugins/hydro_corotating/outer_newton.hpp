#pragma once
// The Newton solve of the outer iteration for (sigma, C_B) (physics-notes §4.4, static form): at each
// axis point P the Bernoulli equation in squared form
//   F_P(sigma, C_B) = h_P^2 alpha_P(sigma)^2 - C_B^2 = 0,
// with h = 1 at the surface point xhat = 1 and h = h_max at xhat_C, and the sigma-model
//   alpha_P(sigma) = alpha_P + alpha_m(rhat_P; sigma) - alpha_m(rhat_P; sigma_old)   (§4.5, model C).
// Full Newton steps, derivative in sigma by a central difference of the model; a trial sigma at
// which the model has no solution (above the fold, §2.2) halves the step.
#include <functional>
#include <vector>

namespace bhnsid::hydro_corotating {

struct AxisPoint {
  double rhat = 0;      ///< distance from xhat_C, where the model is read
  double alpha = 0;     ///< the lapse of the last field solve there
  double enthalpy = 1;  ///< h the Bernoulli equation must give there
};

/// alpha_m(rhat_P; sigma) for every point, in the order of the points; throws core::RunFailure
/// where the model has no solution.
using AlphaModel = std::function<std::vector<double>(double sigma)>;

struct NewtonResult {
  double sigma = 0, bernoulli = 0;
  int iterations = 0;
};

/// Solves F_P = 0 for two points; throws core::RunFailure (with the last iterate) when Newton does
/// not converge in 50 iterations or C_B would not be positive.
NewtonResult solve_sigma_bernoulli(const std::vector<AxisPoint>& points, const AlphaModel& model, double sigma_old);

}  // namespace bhnsid::hydro_corotating

namespace bhnsid::hydro_corotating {

/// One axis point of the corotating (3-point) solve (physics-notes §4.4): the fields of the last
/// field solve there and the enthalpy the Bernoulli equation must give.
struct OrbitPoint {
  double x = 0;         ///< xhat of the point (1, xhat_A or xhat_C)
  double rhat = 0;      ///< distance from xhat_C, where the model is read
  double alpha = 0;     ///< lapse
  double phi = 1;       ///< conformal factor
  double beta_y = 0;    ///< shift (beta^x = beta^z = 0 on the axis by symmetry)
  double enthalpy = 1;  ///< h: 1 at the surface points, h_max at xhat_C
};

/// alpha_m(rhat_P; sigma) and phi_m(rhat_P; sigma) per point; throws core::RunFailure where the model
/// has no solution (above the fold).
struct ModelValues {
  std::vector<double> alpha, phi;
};
using FieldModel = std::function<ModelValues(double sigma)>;

struct OrbitResult {
  double sigma = 0, omega_hat = 0, bernoulli = 0;
  int iterations = 0;
};

/// Solves, for three points,
///   F_P = h_P^2 [alpha_P(s)^2 - phi_P(s)^4 (beta^y_P + xhat_P Omegahat)^2] - C_B^2 = 0,
/// alpha_P(s) = alpha_P + alpha_m(rhat_P; s) - alpha_m(rhat_P; sigma_old) (model C), phi likewise, by
/// Newton from (sigma_old, omega_start, c_start): analytic in Omegahat and C_B, d/dsigma by a central
/// difference of the model (1e-6 sigma). Full steps; a step is halved when the model has no solution
/// at the trial sigma or the trial Omegahat is not > 0 (the root with the star moving in +y is kept,
/// physics-notes §1.2). Throws core::RunFailure when it does not converge in 50 iterations, the
/// Jacobian is singular or C_B would not be positive.
OrbitResult solve_sigma_omega_bernoulli(const std::vector<OrbitPoint>& points, const FieldModel& model, double sigma_old,
                                        double omega_start, double c_start);

}  // namespace bhnsid::hydro_corotating
