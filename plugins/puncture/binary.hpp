#pragma once
// The black hole of a BH/NS binary, set from the star every outer iteration (physics-notes §1.4,
// §4.6), so that no hydro plugin carries it:
//   Mhat_BH = mu_bn M_NS(M0) / sigma   (M_NS: the ADM mass of the isolated TOV star of the physical
//                                       rest mass M0, from the TOV family),
//   xhat_BH = -xhat_C / mu_bn          (the Newtonian centre of mass at the origin),
//   Phat_y  = -sigma^2 Int phi^10 j^y d^3xhat   (zero total linear momentum, eq. phyhat).
#include <array>
#include <string>

#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "bhnsid/interfaces/tov_family.hpp"

namespace bhnsid::puncture {

struct HoleValues {
  double mass = 0;
  std::array<double, 3> position{}, momentum{};
  std::string moved;  ///< non-empty when the position was nudged off a grid point (what and why)
};

/// Mhat_BH and xhat_BH from the fluid's rest mass (`rest_mass`), sigma and xhat_C; momentum left 0.
HoleValues scaled_hole(const Grid& grid, const Fluid& fluid, const TovFamily& family, double mass_ratio,
                       double rest_mass);

/// With mass_target = irreducible: the bare mass that brings the horizon's M_irr to `target` (hatted),
/// from the M_irr measured with `bare_now`. M_irr is nearly proportional to Mhat_BH (M_irr ~ Mhat (1 +
/// M_NS/(2d)) + P^2/(8 Mhat) at Newtonian order), so one ratio step per outer iteration converges
/// with the outer loop. core::RunFailure when M_irr is not a positive number (no horizon).
double irreducible_bare_mass(double bare_now, double irreducible_now, double target);

/// Phat_y = -sigma^2 Int phi^10 j^y d^3xhat on the finest level, with the fluid's projections
/// refreshed from the current fields and phi = puncture_phi + chi.
double balancing_momentum(Grid& grid, const Fluid& fluid);

}  // namespace bhnsid::puncture
