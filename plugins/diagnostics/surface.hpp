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

/// The part of M_ADM's volume integral outside the cube, sigma Int_outside phi^-7 AA/(16 pi), from the
/// face values of AA (phi = 1 beyond the faces). A field AA ~ A(n)/r^p leaves
///   Int_outside A/r^p d^3x = (1/(p-3)) oint AA (x - centre).dS.
/// The far field is split: the Bowen-York AA of the net linear momentum P_net (measured at the faces)
/// falls like r^-4 (a single boosted hole: (15/8) P^2/r_c, first order in 1/r_c); what remains, the
/// whole AA of a binary with zero total momentum, falls like r^-6 (Ahat ~ r^-3), factor 1/3. The
/// cross term (r^-5, factor 1/2) is counted with the rest: an error of O(P_net Q / r_c^2).
struct OutsideMass {
  double net_momentum = 0;  ///< the r^-4 part, from P_net
  double remainder = 0;     ///< the r^-6 part
  double total() const { return net_momentum + remainder; }
};
/// M_ADM from the flux of the conformal factor through the faces (the paper's surface estimate,
/// §6.1): M = -(1/2pi) oint d_i psi dS^i with psi = chi + Mhat_BH/(2 r_BH), whose puncture part
/// contributes Mhat_BH exactly; d_n chi one-sided at second order. Physical units with sigma.
double surface_flux_mass(const Grid& grid, double sigma, double bare_mass_hat);

OutsideMass outside_aa_mass(const Grid& grid, double sigma, const std::array<double, 3>& centre,
                            const std::array<double, 2>& net_momentum_hat);

}  // namespace bhnsid::diagnostics
