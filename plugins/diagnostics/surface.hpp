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

/// The part of M_ADM's volume integral outside the cube, sigma Int_outside phi^-7 AA/(16 pi): with a net
/// momentum P the Bowen-York AA falls off only like r^-4 and that part is (15/8) P^2/r_c for a sphere,
/// a first-order error in 1/r_c. Taking AA ~ A(n)/r^4 about `centre` beyond the faces and phi = 1:
///   Int_outside A/r^4 d^3x = Int A(n)/r_face(n) dOmega = oint AA (x - centre).dS,
/// a surface integral of the face values; what it leaves is O(P^2 M/r_c^2) and the faster-falling Zhat.
double outside_aa_mass(const Grid& grid, double sigma, const std::array<double, 3>& centre);

}  // namespace bhnsid::diagnostics
