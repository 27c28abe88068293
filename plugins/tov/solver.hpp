#pragma once
// The TOV integrator of the tov plugin: one static spherical star of a barotropic EOS, in isotropic
// coordinates (README.md gives the equations).
#include <string>

#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/tov_family.hpp"

namespace bhnsid::tov {

struct Settings {
  /// Relative local error tolerance of the Dormand-Prince 5(4) steps.
  double tolerance = 1e-12;
  /// The step in s = sqrt(ln h_c - ln h) is at most s_surface / min_steps (so the profiles have at
  /// least min_steps + 1 points).
  int min_steps = 256;
  /// Fixed-step mode (for the convergence-order test): > 0 takes this many equal steps, without
  /// error control, in t with s = s_surface sinh(B t) / sinh(B) (geometric near the centre).
  int fixed_steps = 0;
};

/// Integration statistics of one solve.
struct Stats {
  int accepted = 0, rejected = 0;
};

/// The star of central rest-mass density rho_c; throws core::RunFailure if the EOS or the
/// integration fails (e.g. a central density where h(rho_c) <= 1).
TovStar solve_star(const Eos& eos, double central_density, const Settings& settings, Stats* stats = nullptr);

/// The exterior Schwarzschild solution in isotropic coordinates, for r_iso >= the isotropic radius.
double exterior_psi(double adm_mass, double r_iso);
double exterior_lapse(double adm_mass, double r_iso);
/// The isotropic radius of areal radius r outside a mass M: (r - M + sqrt(r^2 - 2 M r)) / 2.
double isotropic_radius_of(double adm_mass, double r_areal);

/// tov_profile.tsv: the interior profile, then `exterior_points` points of the exterior solution out
/// to outer_factor x the isotropic radius (none if exterior_points == 0).
std::string profile_table(const TovStar& star, int exterior_points, double outer_factor);

}  // namespace bhnsid::tov
