#pragma once
// The corotating flow, as the irrotational flow's first outer steps of a cold start use it. A cold
// start's first potential is solved before the shift has felt any momentum (B = Omegahat xi alone);
// close to a heavy hole the star then moves near the light cylinder of that frame, the potential
// comes out several times its settled size, and the Newton step finds no C_B > 0 (mu_bn = 10). The
// corotating flow needs no potential and has the same velocity at the star's centre: a few outer
// steps of it give the shift the orbit's momentum before the potential is first solved. Corotation:
//   U = B = beta + Omegahat xi,  D = alpha^2 - phi^4 |U|^2,  W = alpha / sqrt(D),  v^i = U^i / alpha,
//   first integral h sqrt(D) = C_B (h/u^t, u^t = 1/sqrt(D)).
#include <cmath>
#include <limits>

namespace bhnsid::flow_irrotational::corotating_start {

/// D = alpha^2 - phi^4 |U|^2 (NaN where alpha <= 0 or D <= 0: no observer corotates there).
inline double frame_norm(double alpha, double phi, const double u[3]) {
  const double phi2 = phi * phi;
  const double d = alpha * alpha - phi2 * phi2 * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  return alpha > 0 && d > 0 ? d : std::numeric_limits<double>::quiet_NaN();
}

/// The first integral's enthalpy h = C_B / sqrt(D); -1 where D is not positive.
inline double enthalpy(double alpha, double phi, const double u[3], double bernoulli) {
  const double d = frame_norm(alpha, phi, u);
  return std::isfinite(d) ? bernoulli / std::sqrt(d) : -1.0;
}

/// F_P = h_P^2 D_P - C_B^2 at an axis point (U = beta^y + xhat Omegahat along y, beta frozen) and its
/// derivatives in Omegahat and C_B.
inline void axis_residual(double x, double beta_y, double alpha, double phi, double omega_hat, double bernoulli,
                          double enthalpy, double out[3]) {
  const double h2 = enthalpy * enthalpy, phi2 = phi * phi, u = beta_y + x * omega_hat;
  out[0] = h2 * (alpha * alpha - phi2 * phi2 * u * u) - bernoulli * bernoulli;
  out[1] = -2.0 * h2 * phi2 * phi2 * u * x;
  out[2] = -2.0 * bernoulli;
}

}  // namespace bhnsid::flow_irrotational::corotating_start
