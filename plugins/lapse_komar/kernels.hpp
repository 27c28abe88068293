#pragma once
// Point function of maximal slicing with a singular puncture term (the lapse of Shibata & Uryu
// 2006 and Kyutoku, Shibata & Taniguchi 2009 in this code's variables, docs/lapse.md):
//   eta = alpha phi = eta~ - c Mhat_BH/(2 rhat_BH),   eta~ regular,
//   lap eta~ - kappa (eta~ - c Mhat_BH/(2 rhat_BH)) = 0,
//   kappa = (7/8) phi^-8 AA + 2 pi sigma^2 phi^4 (rho_E + 2S),
// which is eq. maxslice_hat for eta, since lap(Mhat/(2 rhat)) = 0 off the puncture. Mhat/(2 rhat) is
// the hamiltonian's puncture_phi field, and kappa ~ rhat^4 there, so the source kappa c puncture_phi
// ~ rhat^3 is regular: the same operator as the paper's lapse, nothing excised.
#include <cstddef>
#include <numbers>

#include "bhnsid/interfaces/scalar_sweep.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::lapse_komar {

/// Arrays of one level the local term reads; matter only with a fluid.
struct Sources {
  const double* chi = nullptr;
  const double* puncture_phi = nullptr;
  const double* aa = nullptr;
  MatterSources matter;  ///< rho_E and S from the star, refreshed before the sweep
  double c = 1;          ///< the strength of the singular term (1: static; the virial value otherwise)
};

/// N(eta~) = -kappa (eta~ - c puncture_phi) and dN/deta~ = -kappa at fixed rho_E and S.
template <bool Matter>
struct KomarTerm {
  static constexpr bool linear = false;
  Sources s;
  stencil::LocalTerm at(std::ptrdiff_t idx, double eta_regular) const {
    const double phi = s.puncture_phi[idx] + s.chi[idx];
    const double inv_phi = 1.0 / phi;
    const double inv4 = (inv_phi * inv_phi) * (inv_phi * inv_phi);
    double k = 0.875 * s.aa[idx] * inv4 * inv4;
    if constexpr (Matter) {
      const MatterSources& m = s.matter;
      const double phi2 = phi * phi;
      k += 2.0 * std::numbers::pi * m.sigma2 * (m.energy[idx] + 2.0 * m.trace[idx]) * (phi2 * phi2);
    }
    return {-k * (eta_regular - s.c * s.puncture_phi[idx]), -k};
  }
};

/// alpha = (eta~ - c puncture_phi) / (puncture_phi + chi): -c at the puncture, 0 on the sphere where
/// eta~ = c Mhat/(2 rhat) (the isotropic horizon rhat = c Mhat/2 of a lone hole), 1 far away.
inline double alpha_of(double eta_regular, double chi, double puncture_phi, double c) {
  return (eta_regular - c * puncture_phi) / (puncture_phi + chi);
}

}  // namespace bhnsid::lapse_komar
