#pragma once
// The family of static spherical stars (Tolman-Oppenheimer-Volkoff solutions) of one equation of
// state, published by the tov plugin under the capability "tov_family".
//
// Units: the code's units G = c = 1 with the EOS's own scale (K = 1 for the paper's polytropes).
// These are the PHYSICAL units, never the hatted (sigma-rescaled) ones: to find the isolated star of
// a hatted rest mass Mhat0, look up the physical M0 = sigma * Mhat0 and divide the ADM mass it gives
// by sigma (physics-notes section 1.4, "Trap in eq. bh_mass"). The one exception is frozen_profile,
// the sigma model, which works in hatted radius with the matter in physical units (section 1.3).
//
// Coordinates: isotropic, gamma_ij = psi^4 delta_ij, with r_iso the isotropic radius; outside the
// star psi = 1 + M/(2 r_iso) and alpha = (1 - M/(2 r_iso)) / (1 + M/(2 r_iso)).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "bhnsid/core/services.hpp"

namespace bhnsid {

/// One TOV star: its scalars and its interior profiles from the centre (r_iso = 0) to the surface
/// (r_iso = radius_isotropic, rho0 = 0), all vectors of the same length, r_iso increasing.
struct TovStar {
  double central_density = 0;   ///< rho0 at the centre
  double adm_mass = 0;          ///< gravitational (ADM) mass M
  double rest_mass = 0;         ///< rest (baryon) mass M0 = Int rho0 u^t sqrt(-g) d^3x
  double radius_areal = 0;      ///< Schwarzschild (areal) radius R of the surface
  double radius_isotropic = 0;  ///< isotropic radius of the surface, (R - M + sqrt(R^2 - 2 M R)) / 2
  double lapse_center = 0;      ///< alpha at the centre
  double psi_center = 0;        ///< conformal factor psi at the centre
  std::vector<double> r_iso, psi, alpha, rho0;
  std::vector<double> r_areal;  ///< the areal radius r at each profile point (psi = sqrt(r / r_iso))
};

/// Model C (physics-notes section 4.5, "frozen-profile TOV"): the spherical hatted field equations
///   phi'' + (2/r) phi' + 2 pi sigma^2 phi^5 E = 0,   eta'' + (2/r) eta' - 2 pi sigma^2 phi^4 (E + 2S) eta = 0,
/// regular at rhat = 0 and u -> 1 at infinity, with a FIXED source: E = e and E + 2S = e + 6P (static,
/// W = 1) of the TOV star of central density rho_max, stretched so that its surface sits at hatted
/// radius rhat_star (r_iso = rhat R_iso / rhat_star). At sigma_tov = R_iso / rhat_star it is the TOV
/// star itself; above a fold sigma_fold > sigma_tov it has no solution (physics-notes section 2.2).
/// alpha = eta / phi.
struct FrozenProfileSolution {
  double sigma = 0;
  double sigma_tov = 0;  ///< R_iso / rhat_star of the frozen star
  /// Increasing rhat from 0 to the outer radius of the 1-D grid (the tov plugin ends it at rhat_star:
  /// outside the matter the solution is exactly u = 1 + c/rhat, which phi_at/alpha_at continue).
  std::vector<double> rhat, phi, alpha;
  /// Cubic interpolation (even in rhat at the centre); beyond the last point the source-free exterior
  /// u = 1 + c/rhat of phi and eta = alpha phi, with c from the last point. Needs >= 4 points.
  double phi_at(double rhat) const;
  double alpha_at(double rhat) const;
};

namespace detail {

/// Cubic Lagrange interpolation of y(x) at xq from the four nodes around it (x strictly increasing,
/// at least 4 nodes, x[0] = 0 when even_at_zero: y is taken even in x, so the node left of 0 is the
/// mirror of x[1]). Outside [x.front(), x.back()] it extrapolates the end cubic.
inline double interpolate_cubic(const std::vector<double>& x, const std::vector<double>& y, double xq,
                                bool even_at_zero) {
  const auto n = static_cast<std::ptrdiff_t>(x.size());
  if (n < 4 || y.size() != x.size()) return std::numeric_limits<double>::quiet_NaN();
  std::ptrdiff_t j = std::upper_bound(x.begin(), x.end(), xq) - x.begin() - 1;  // x[j] <= xq < x[j+1]
  j = std::clamp<std::ptrdiff_t>(j, 0, n - 2);
  std::ptrdiff_t first = j - 1;
  if (!(even_at_zero && first == -1)) first = std::clamp<std::ptrdiff_t>(first, 0, n - 4);
  double xs[4], ys[4];
  for (int k = 0; k < 4; ++k) {
    const std::ptrdiff_t i = first + k;
    xs[k] = i < 0 ? -x[static_cast<std::size_t>(-i)] : x[static_cast<std::size_t>(i)];
    ys[k] = y[static_cast<std::size_t>(i < 0 ? -i : i)];
  }
  double sum = 0;
  for (int k = 0; k < 4; ++k) {
    double l = 1;
    for (int m = 0; m < 4; ++m)
      if (m != k) l *= (xq - xs[m]) / (xs[k] - xs[m]);
    sum += l * ys[k];
  }
  return sum;
}

}  // namespace detail

inline double FrozenProfileSolution::phi_at(double r) const {
  r = std::fabs(r);
  if (rhat.size() < 4) return std::numeric_limits<double>::quiet_NaN();
  if (r <= rhat.back()) return detail::interpolate_cubic(rhat, phi, r, true);
  return 1.0 + rhat.back() * (phi.back() - 1.0) / r;
}

inline double FrozenProfileSolution::alpha_at(double r) const {
  r = std::fabs(r);
  if (rhat.size() < 4) return std::numeric_limits<double>::quiet_NaN();
  if (r <= rhat.back()) return detail::interpolate_cubic(rhat, alpha, r, true);
  const double c_phi = rhat.back() * (phi.back() - 1.0);
  const double c_eta = rhat.back() * (alpha.back() * phi.back() - 1.0);
  return (1.0 + c_eta / r) / (1.0 + c_phi / r);
}

class TovFamily : public core::Service {
 public:
  ~TovFamily() override;  ///< defined in the core library (see grid.hpp)

  /// The star of central rest-mass density rho0_c > 0.
  virtual TovStar star(double central_density) const = 0;
  /// The ADM mass of the star of rest mass M0 on the stable branch (central density below that of
  /// the maximum-mass star). Throws core::RunFailure when M0 <= 0 or M0 exceeds the maximum rest mass.
  virtual double adm_mass_from_rest_mass(double rest_mass) const = 0;
  /// The stable-branch star of rest mass M0 (the star adm_mass_from_rest_mass measures).
  virtual TovStar star_from_rest_mass(double rest_mass) const = 0;
  /// The star of largest ADM mass, and the star of largest rest mass. For a cold barotropic EOS the
  /// two extrema lie at the same central density (turning-point theorem), up to the search tolerance.
  virtual TovStar maximum_mass_star() const = 0;
  virtual TovStar maximum_rest_mass_star() const = 0;
  /// Model C (physics-notes section 4.5): the frozen-profile solution for the TOV star of central
  /// density rho_max with its surface at hatted radius rhat_star, at scaling factor sigma. Continuous
  /// and smooth in sigma (a fixed radial grid per (rho_max, rhat_star)), cached, thread safe; cheap
  /// after the first call (for finite differences in sigma). Throws core::RunFailure when sigma is
  /// above the fold (no solution), naming sigma and the fold, or when the inputs are not positive.
  virtual FrozenProfileSolution frozen_profile(double rho_max, double rhat_star, double sigma) const = 0;
};

}  // namespace bhnsid
