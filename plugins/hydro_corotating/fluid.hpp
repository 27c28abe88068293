#pragma once
// The "hydro" service of the corotating star: its constants and the matter projections that the
// field equations read, formed from the star's rho0, P, h and the current chi, alpha, beta with the
// kinematics of corotation (kinematics.hpp).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::hydro_corotating {

/// The constants the outer iteration solves for.
struct StarConstants {
  double sigma = 0;
  double bernoulli = 0;  ///< C_B
  double omega_hat = 0;  ///< Omegahat
  double x_c = 0;        ///< xhat_C, the density maximum on the x axis
};

class StarFluid final : public Fluid {
 public:
  double sigma() const override { return constants.sigma; }
  std::array<double, 3> centre() const override { return {constants.x_c, 0.0, 0.0}; }
  std::array<double, 3> falloff_centre() const override { return {robin_centre, 0.0, 0.0}; }
  double omega_hat() const override { return constants.omega_hat; }
  double bernoulli_constant() const override { return constants.bernoulli; }
  double rest_mass() const override;
  double initial_rest_mass() const override { return initial_mass; }
  bool settled() const override { return converged; }
  std::vector<std::string> source_inputs() const override { return {fields::rho0, fields::press, fields::enthalpy}; }
  void update_sources(Grid& grid, int level) const override;

  /// A point of matter where the corotating flow |beta + Omegahat xi| phi^2 / alpha reaches the
  /// speed of light in the current fields (W undefined), if there is one: why rest_mass() is NaN.
  std::optional<std::array<double, 3>> superluminal_matter() const;

  /// Registers the fluid fields and the projections on `grid` (every level); alpha comes from `lapse`.
  void attach(Grid& grid, const Lapse& lapse);

  StarConstants constants;
  double robin_centre = 0;  ///< fixed at the initial xhat_C: the solver builds its boundary once
  double initial_mass = 0;  ///< M0 of the TOV star of rho_max, the initial guess
  bool converged = false;   ///< the last outer step converged and was not applied

 private:
  Grid* grid_ = nullptr;
  int rho0_ = -1, press_ = -1, enthalpy_ = -1, energy_ = -1, trace_ = -1, momentum_ = -1;
  const Lapse* lapse_ = nullptr;
  int chi_ = -1, puncture_phi_ = -1;
};

}  // namespace bhnsid::hydro_corotating
