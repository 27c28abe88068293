#pragma once
// The black hole's diagnostics: surface integrals of Ahat at the outer faces (physics-notes §1.4,
// §2.6) and chi at the puncture.
#include <array>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::diagnostics {

struct SurfaceMomenta {
  double momentum_x = 0, momentum_y = 0;  ///< P^i = (sigma/8pi) oint Ahat^ij dS_j (P^z = 0 by symmetry)
  double angular_momentum_z = 0;          ///< J_z = (sigma^2/8pi) oint (x Ahat^yj - y Ahat^xj) dS_j
};

/// From the field ahat (6 components) on the finest level; physical units with sigma. At the
/// faces K^ij -> Ahat^ij (phi -> 1), so these are the ADM linear and angular momenta up to
/// O(1/r_c) from phi - 1 (which the matter integrals in the binary issue complement).
SurfaceMomenta surface_momenta(const Grid& grid, double sigma);

}  // namespace bhnsid::diagnostics
