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
