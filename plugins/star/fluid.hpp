#pragma once
// The "star" service: the star's constants and its matter as the field equations read it. The
// density, pressure and enthalpy are the star's; W, v^i and the projections come from the flow
// (Flow, capability "flow"), so that the equations never see how the fluid moves.
#include <array>
#include <string>
#include <vector>

#include "bhnsid/interfaces/flow.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::star {

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
  std::vector<std::string> source_inputs() const override;
  void update_sources(Grid& grid, int level) const override;

  /// Registers the fluid fields and the projections on `grid` (every level); the kinematics are `flow`'s.
  void attach(Grid& grid, Flow& flow);
  Flow& flow() const { return *flow_; }
  /// The constants as the flow reads them.
  FlowConstants flow_constants() const { return {constants.sigma, constants.omega_hat, constants.bernoulli}; }

  StarConstants constants;
  double robin_centre = 0;  ///< fixed at the initial xhat_C: the solver builds its boundary once
  double initial_mass = 0;  ///< M0 of the TOV star of rho_max, the initial guess
  bool converged = false;   ///< the last outer step converged and was not applied

 private:
  Grid* grid_ = nullptr;
  Flow* flow_ = nullptr;
  int rho0_ = -1, chi_ = -1, puncture_phi_ = -1;
};

}  // namespace bhnsid::star
