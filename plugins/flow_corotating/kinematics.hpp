#pragma once
// The kinematics of corotation (physics-notes §1.2, §2.1): the fluid's coordinate velocity is
// dx^i/dt = Omegahat xi^i, xi = (-yhat, xhat, 0), so that the Eulerian velocity is
//   v^i = U^i / alpha,  U^i = beta^i + Omegahat xi^i,  alpha from the "lapse" service,
//   W^2 = 1 / (1 - phi^4 |v|^2) = 1 / (1 - phi^4 |U|^2 / alpha^2),
// and the matter projections the field equations read are
//   rho_E = rho0 h W^2 - P,  S = rho0 h (W^2 - 1) + 3 P,  j^i = rho0 h W^2 v^i.
// These are the only formulas an irrotational plugin would replace (its W and v^i come from the
// velocity potential); no field equation repeats them.
#include <cstddef>
#include <limits>

namespace bhnsid::flow_corotating {

/// W^2 from phi, alpha and U; NaN where the corotating velocity is superluminal (far outside the
/// star, where it is never used) and where alpha <= 0 (inside the hole's horizon, where no observer
/// corotates). A constant NaN, not std::nan(""): a library call keeps loops scalar.
inline double lorentz_squared(double phi, double alpha, double ux, double uy, double uz) {
  const double phi2 = phi * phi;
  const double v2 = phi2 * phi2 * (ux * ux + uy * uy + uz * uz) / (alpha * alpha);
  return v2 < 1.0 && alpha > 0 ? 1.0 / (1.0 - v2) : std::numeric_limits<double>::quiet_NaN();
}

/// The projections at one point (rho0 > 0).
struct Projections {
  double energy, trace, jx, jy, jz;
};

inline Projections projections(double rho0, double press, double enthalpy, double lorentz2, double alpha, double ux,
                               double uy, double uz) {
  const double rho_h = rho0 * enthalpy, rho_hw2 = rho_h * lorentz2, inv_alpha = 1.0 / alpha;
  return {rho_hw2 - press, rho_h * (lorentz2 - 1.0) + 3.0 * press, rho_hw2 * ux * inv_alpha, rho_hw2 * uy * inv_alpha,
          rho_hw2 * uz * inv_alpha};
}

}  // namespace bhnsid::flow_corotating
