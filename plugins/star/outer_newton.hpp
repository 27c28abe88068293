#pragma once
// The Newton solve of the outer iteration (physics-notes §4.4): at each axis point P the flow's
// first-integral residual F_P (Flow::axis_residual; for corotation
//   F_P = h_P^2 [alpha_P^2 - phi_P^4 (beta^y_P + xhat_P Omegahat)^2] - C_B^2)
// vanishes, with h = 1 at the surface points and h = h_max at xhat_C, and the sigma-model
//   alpha_P(sigma) = alpha_P + alpha_m(rhat_P; sigma) - alpha_m(rhat_P; sigma_old)   (§4.5, model C),
// phi likewise. Analytic in Omegahat and C_B (the flow's derivatives), d/dsigma by a central
// difference of the model (1e-6 sigma). Full Newton steps; a trial sigma at which the model has no
// solution (above the fold, §2.2) halves the step.
#include <functional>
#include <vector>

#include "bhnsid/interfaces/flow.hpp"

namespace bhnsid::star {

/// One axis point: the fields of the last field solve there and the enthalpy the first integral
/// must give.
struct AxisPoint {
  double rhat = 0;      ///< distance from xhat_C, where the model is read
  double alpha = 0;     ///< lapse
  double phi = 1;       ///< conformal factor
  double enthalpy = 1;  ///< h: 1 at the surface points, h_max at xhat_C
};

/// alpha_m(rhat_P; sigma) and phi_m(rhat_P; sigma) per point; throws core::RunFailure where the model
/// has no solution (above the fold).
struct ModelValues {
  std::vector<double> alpha, phi;
};
using FieldModel = std::function<ModelValues(double sigma)>;

/// F_P of point p for the modelled (alpha, phi) and trial (Omegahat, C_B), the point's enthalpy last.
using PointResidual = std::function<AxisResidual(std::size_t p, double alpha, double phi, double omega_hat,
                                                 double bernoulli, double enthalpy)>;

struct NewtonResult {
  double sigma = 0, omega_hat = 0, bernoulli = 0;
  int iterations = 0;
};

/// Two points (the centre, then the surface point xhat = 1) for (sigma, C_B) at a fixed Omegahat:
/// the single star (physics-notes §9 T1). Starts from (sigma_old, c_start). Throws
/// core::RunFailure when Newton does not converge in 50 iterations, the matrix is singular or C_B
/// would not be positive.
NewtonResult solve_sigma_bernoulli(const std::vector<AxisPoint>& points, const FieldModel& model,
                                   const PointResidual& residual, double sigma_old, double omega_hat, double c_start);

/// Three points (xhat = 1, xhat_A, xhat_C) for (sigma, Omegahat, C_B), from (sigma_old, omega_start,
/// c_start). A step is also halved when the trial Omegahat is not > 0 (the root with the star moving
/// in +y is kept, physics-notes §1.2). Throws core::RunFailure as above.
NewtonResult solve_sigma_omega_bernoulli(const std::vector<AxisPoint>& points, const FieldModel& model,
                                         const PointResidual& residual, double sigma_old, double omega_start,
                                         double c_start);

}  // namespace bhnsid::star
