#pragma once
// The family of static spherical stars (Tolman-Oppenheimer-Volkoff solutions) of one equation of
// state, published by the tov plugin under the capability "tov_family".
//
// Units: the code's units G = c = 1 with the EOS's own scale (K = 1 for the paper's polytropes).
// These are the PHYSICAL units, never the hatted (sigma-rescaled) ones: to find the isolated star of
// a hatted rest mass Mhat0, look up the physical M0 = sigma * Mhat0 and divide the ADM mass it gives
// by sigma (physics-notes section 1.4, "Trap in eq. bh_mass").
//
// Coordinates: isotropic, gamma_ij = psi^4 delta_ij, with r_iso the isotropic radius; outside the
// star psi = 1 + M/(2 r_iso) and alpha = (1 - M/(2 r_iso)) / (1 + M/(2 r_iso)).
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
  // Later (physics-notes section 4.5, model C): the sigma-modelling solves, i.e. the spherical hatted
  // field equations with source sigma^2 x the frozen profile of the star with rho_c = (rho0)_max,
  // giving alpha_m(rhat; sigma) and phi_m(rhat; sigma). They will be declared here.
};

}  // namespace bhnsid
