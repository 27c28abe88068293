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

/// Arrays of one level the local term reads; matter only with a fluid.
struct Sources {
  const double* chi = nullptr;
  const double* puncture_phi = nullptr;
  const double* aa = nullptr;
  MatterSources matter;     ///< rho_E and S from the star, refreshed before the sweep
  double matter_scale = 1;  ///< 1 except in the IRE sensitivity test
};

/// N(eta) = -eta k(x) and dN/deta = -k at fixed rho_E and S (they depend on eta only through W, a
/// small term that the next sweep's refreshed projections correct).
/// Matter = false (no fluid): the matter term and its arrays are left out of the sweep.
template <bool Matter>
struct LapseTerm {
  static constexpr bool linear = false;
  Sources s;
  stencil::LocalTerm at(std::ptrdiff_t idx, double eta) const {
    const double phi = s.puncture_phi[idx] + s.chi[idx];
    const double inv_phi = 1.0 / phi;
    const double inv4 = (inv_phi * inv_phi) * (inv_phi * inv_phi);
    double k = 0.875 * s.aa[idx] * inv4 * inv4;
    if constexpr (Matter) {
      // The projections are 0 outside the matter (the star writes them so).
      const MatterSources& m = s.matter;
      const double phi2 = phi * phi;
      k += 2.0 * std::numbers::pi * m.sigma2 * s.matter_scale * (m.energy[idx] + 2.0 * m.trace[idx]) * (phi2 * phi2);
    }
    return {-eta * k, -k};
  }
};

}  // namespace bhnsid::lapse
