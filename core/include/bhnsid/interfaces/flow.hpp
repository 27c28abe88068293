#pragma once
// How the star's fluid moves, published by a flow plugin under "flow" (Flow). The star (capability
// "star") owns the density, the constants (sigma, Omegahat, C_B), the Newton solve for them and the
// Bernoulli reset; a flow owns only the kinematics (W, v^i), the matter projections the field
// equations read, and its first integral h = C_B G. Corotation and irrotational flow are two flows
// under one star, swapped by the parameter file. Hatted coordinates throughout; xi = (-yhat, xhat, 0)
// is the rotation about the z axis through the origin, B = beta + Omegahat xi the corotating frame's
// shift.
#include <cstddef>
#include <string>
#include <vector>

#include "bhnsid/core/services.hpp"
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid {

/// The star's constants as a flow reads them: those of the last field solve, or trial values of
/// the Newton solve.
struct FlowConstants {
  double sigma = 1;
  double omega_hat = 0;  ///< Omegahat
  double bernoulli = 0;  ///< C_B, the constant of the first integral
};

/// F_P of one axis point of the star's Newton solve (a residual that vanishes where the first
/// integral gives the enthalpy h_P the point must have) and its derivatives in Omegahat and C_B.
/// The star takes d/dsigma through its sigma-model of alpha and phi.
struct AxisResidual {
  double f = 0, df_domega = 0, df_dbernoulli = 0;
};

class Flow : public core::Service {
 public:
  ~Flow() override;  ///< defined in the core library (see grid.hpp)
  /// One word for the log and the output ("corotating", "irrotational").
  virtual std::string kind() const = 0;
  /// Grid fields of its own the projections read on every level (beyond rho0, press, enthalpy and
  /// the metric), so that the equations list them as coefficients and the solver restricts them.
  virtual std::vector<std::string> source_inputs() const { return {}; }

  /// Called by the star at the start of each outer step, after the field solve, with the constants
  /// the step starts from (a first guess of Omegahat where none is known yet): a flow with a field
  /// of its own (a velocity potential) solves it here. Returns how much that field changed, relative
  /// (0 for a flow without one): a star whose density is held (`iterate: false`) is settled only once
  /// the flow is.
  virtual double prepare(Grid& /*grid*/, const FlowConstants& /*c*/) { return 0.0; }
  /// Called by the star after its Newton step with the constants it moves to, before its reset: a
  /// flow whose own field depends on them (a potential on Omegahat) moves it as its axis model did,
  /// so that the reset and the next field solve see the flow the Newton step assumed.
  virtual void set_constants(Grid& /*grid*/, const FlowConstants& /*c*/) {}

  /// rho_E, S and j^i (fields::matter_energy, matter_trace, matter_momentum) on `level` from rho0,
  /// press, enthalpy and the current chi, alpha, beta of that level; 0 where rho0 = 0. One call per
  /// sweep.
  virtual void update_sources(Grid& grid, int level, const FlowConstants& c) const = 0;

  /// W and the Eulerian (Valencia) velocity v^i at every stored point of the finest level (no
  /// ghosts): W = 1 and v = 0 where rho0 = 0; W = NaN at matter where the flow has no timelike
  /// velocity in the current fields. `v` may be null (W only).
  virtual void velocity(Grid& grid, const FlowConstants& c, double* lorentz, double* const* v) const = 0;

  /// Where matter has no timelike velocity (W NaN above), in words with the point, for the star's
  /// error message; empty when there is none.
  virtual std::string acausal_matter(Grid& grid, const FlowConstants& c) const = 0;

  /// The first integral's enthalpy h = C_B G at every stored point of the finest level, given the
  /// lapse and conformal factor the star models (`alpha`, `phi`: finest-level arrays) and the flow's
  /// own current fields; -1 where G is undefined (no such flow can hold matter there: near the
  /// hole, beyond the light cylinder).
  virtual void enthalpy(Grid& grid, const FlowConstants& c, const double* alpha, const double* phi, double* h) const = 0;

  /// The first integral's constant as the current fields give it at every stored point of the
  /// finest level where rho0 > 0 (h alpha / W for corotation, h alpha W - B^i d_i Psi for
  /// irrotational flow; C_B at a solution), NaN elsewhere: the IRE's Bernoulli residual.
  virtual void first_integral(Grid& grid, const FlowConstants& c, double* out) const = 0;

  /// True when the flow satisfies rest-mass conservation d_i[rho0 W phi^6 (alpha v^i - B^i)] = 0 by
  /// solving it (so the IRE judges its residual); false when its kinematics make the flux vanish
  /// identically (corotation: alpha v = B).
  virtual bool solves_continuity() const { return false; }

  /// The largest relative change of Omegahat one outer step may make (0: any): a flow whose axis
  /// model linearises its own field about the current Omegahat trusts it that far, and the star
  /// shortens a longer step (every constant the same fraction of the way).
  virtual double omega_step_limit() const { return 0.0; }

  /// The star's Newton solve: freeze what the first integral reads at the axis points xhat = xs[p]
  /// (yhat = zhat = 0) from the last field solve and the flow's own fields, solved at `c`.
  virtual void freeze_axis(Grid& grid, const std::vector<double>& xs, const FlowConstants& c) = 0;
  /// F_P at axis point p of the last freeze_axis for the trial (alpha, phi) of the star's model and
  /// the trial (Omegahat, C_B); `enthalpy` is the h the point must have (1 at the surface, h_max at
  /// the centre). The flow models how its frozen values move with Omegahat.
  virtual AxisResidual axis_residual(std::size_t p, double alpha, double phi, double omega_hat, double bernoulli,
                                     double enthalpy) const = 0;
};

}  // namespace bhnsid
