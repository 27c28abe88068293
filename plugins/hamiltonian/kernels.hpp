#pragma once
// Point functions of the Hamiltonian constraint, eq. ham_hat (physics-notes §2.2):
//   lap chi + (1/8) phi^-7 AA + 2 pi sigma^2 phi^5 rho_E = 0,   phi = Mhat_BH/(2 rhat_BH) + chi.
// They plug into stencil::scalar_residual/scalar_relax as the local term N(chi) and its slope.
#include <cmath>
#include <cstddef>
#include <numbers>

#include "bhnsid/interfaces/scalar_sweep.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::hamiltonian {

/// Arrays of one level that the local term reads; matter only with a fluid.
struct Sources {
  const double* puncture_phi = nullptr;
  const double* aa = nullptr;
  MatterSources matter;     ///< rho_E from the star, refreshed before the sweep
  double matter_scale = 1;  ///< 1 except in the IRE sensitivity test (one coefficient times 1 + eps)
};

/// N(chi) = (1/8) phi^-7 AA + 2 pi sigma^2 phi^5 rho_E and dN/dchi at fixed rho_E (rho_E depends on
/// chi only through W, a small term the next sweep's refreshed rho_E corrects). phi^-1 is formed as
/// 1/(puncture_phi + chi), which is regular (-> 0) at the puncture, so phi^-7 AA ~ r^3 stays finite
/// however close a point comes to the hole (§2.1); the puncture itself is never a grid point.
/// Matter = false (no fluid): the matter term and its array are left out of the sweep.
template <bool Matter>
struct HamiltonianTerm {
  static constexpr bool linear = false;
  Sources s;
  stencil::LocalTerm at(std::ptrdiff_t idx, double chi) const {
    const double phi = s.puncture_phi[idx] + chi;
    const double inv_phi = 1.0 / phi;
    const double inv4 = (inv_phi * inv_phi) * (inv_phi * inv_phi);
    const double inv7 = inv4 * inv_phi * inv_phi * inv_phi;
    const double aa = s.aa[idx];
    double value = 0.125 * aa * inv7, slope = -0.875 * aa * inv7 * inv_phi;
    if constexpr (Matter) {
      // rho_E is 0 outside the matter (the star writes it so), so no select is needed.
      const double phi2 = phi * phi;
      const double c = 2.0 * std::numbers::pi * s.matter.sigma2 * s.matter_scale * s.matter.energy[idx] * (phi2 * phi2);
      value += c * phi;
      slope += 5.0 * c;
    }
    return {value, slope};
  }
};

}  // namespace bhnsid::hamiltonian
