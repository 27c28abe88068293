#pragma once
// Point functions of the maximal-slicing condition for eta = alpha phi, eq. maxslice_hat
// (physics-notes §2.4):
//   lap eta - eta [ (7/8) phi^-8 AA + 2 pi sigma^2 phi^4 (rho_E + 2 S) ] = 0.
// The coefficient of eta is >= 0, so the equation is uniquely solvable and eta is regular at the
// puncture; alpha = eta/phi -> 0 there.
#include <cstddef>
#include <numbers>

#include "bhnsid/interfaces/scalar_sweep.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::lapse {

/// Arrays of one level the local term reads (velocity and shift only for moving matter; shift may
/// be null).
struct Sources {
  const double* chi = nullptr;
  const double* puncture_phi = nullptr;
  const double* aa = nullptr;
  MatterArrays matter;
  double matter_scale = 1;  ///< 1 except in the IRE sensitivity test
};

/// N(eta) = -eta k(x) and dN/deta = -k at fixed W (W depends on eta only through the velocity,
/// a small term in the Newton step that the outer solve corrects).
/// Matter = false (no fluid): the matter term and its three arrays are left out of the sweep.
template <bool Moving, bool Matter = true>
struct LapseTerm {
  static constexpr bool linear = false;
  Sources s;
  stencil::LocalTerm at(std::ptrdiff_t idx, double eta) const {
    const double phi = s.puncture_phi[idx] + s.chi[idx];
    const double inv_phi = 1.0 / phi;
    const double inv4 = (inv_phi * inv_phi) * (inv_phi * inv_phi);
    double k = 0.875 * s.aa[idx] * inv4 * inv4;
    if constexpr (Matter) {
      // Selected, not branched on, so that the sweep vectorises (see hamiltonian/kernels.hpp).
      const MatterArrays& m = s.matter;
      const double rho0 = m.rho0[idx];
      double lorentz2 = 1.0;
      if constexpr (Moving)
        lorentz2 = lorentz_squared(phi, eta, m.coordinate_velocity(0, idx), m.coordinate_velocity(1, idx),
                                   m.coordinate_velocity(2, idx));
      const MatterProjections p = matter_projections(rho0, m.press[idx], m.enthalpy[idx], lorentz2);
      const double phi2 = phi * phi;
      const double k_matter =
          2.0 * std::numbers::pi * m.sigma2 * s.matter_scale * (p.energy + 2.0 * p.trace) * (phi2 * phi2);
      k += rho0 > 0 ? k_matter : 0.0;
    }
    return {-eta * k, -k};
  }
};

}  // namespace bhnsid::lapse
