#pragma once
// Values of one TOV star at any isotropic radius: 4-point Lagrange interpolation of the interior
// profiles, the exterior Schwarzschild solution outside (physics-notes §6.1 conventions).
#include "bhnsid/interfaces/tov_family.hpp"

namespace bhnsid::star {

struct TovPoint {
  double rho0 = 0, psi = 1, alpha = 1;
};

TovPoint tov_at(const TovStar& star, double r_iso);

}  // namespace bhnsid::star
