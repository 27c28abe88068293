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

/// Arrays of one level that the local term reads; velocity and eta only for moving matter, shift
/// may be null (no shift equation active).
struct Sources {
  const double* puncture_phi = nullptr;
  const double* aa = nullptr;
  const double* eta = nullptr;  ///< moving matter only (W needs alpha)
  MatterArrays matter;
  double matter_scale = 1;  ///< 1 except in the IRE sensitivity test (one coefficient times 1 + eps)
};

/// W^2 at one point from the current phi and eta (physics-notes §2.1); 1 for static matter.
template <bool Moving>
inline double lorentz2_at(const Sources& s, std::ptrdiff_t idx, double phi) {
  if constexpr (!Moving) {
    (void)s, (void)idx, (void)phi;
    return 1.0;
  } else {
    const MatterArrays& m = s.matter;
    return lorentz_squared(phi, s.eta[idx], m.coordinate_velocity(0, idx), m.coordinate_velocity(1, idx),
                           m.coordinate_velocity(2, idx));
  }
}

/// N(chi) = (1/8) phi^-7 AA + 2 pi sigma^2 phi^5 rho_E and dN/dchi at fixed W. phi^-1 is formed as
/// 1/(puncture_phi + chi), which is regular (-> 0) at the puncture, so phi^-7 AA ~ r^3 stays finite
/// however close a point comes to the hole (§2.1); the puncture itself is never a grid point.
/// Matter = false (no fluid): the matter term and its three arrays are left out of the sweep.
template <bool Moving, bool Matter = true>
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
      // The matter term is formed at every point and selected, not branched on: a branch keeps GCC
      // from vectorising the sweep. Outside the star (rho0 = 0) W may be NaN (a superluminal
      // corotation velocity far out); the select drops it.
      const MatterArrays& m = s.matter;
      const double rho0 = m.rho0[idx];
      const double e = matter_projections(rho0, m.press[idx], m.enthalpy[idx], lorentz2_at<Moving>(s, idx, phi)).energy;
      const double phi2 = phi * phi;
      const double c_matter = 2.0 * std::numbers::pi * m.sigma2 * s.matter_scale * e * (phi2 * phi2);
      const double c = rho0 > 0 ? c_matter : 0.0;
      value += c * phi;
      slope += 5.0 * c;
    }
    return {value, slope};
  }
};

}  // namespace bhnsid::hamiltonian
