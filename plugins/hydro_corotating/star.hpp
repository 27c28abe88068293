#pragma once
// The corotating star of the hydro_corotating plugin: its constants (sigma, C_B, x_C), the fluid
// fields on the grid, and the outer-iteration step (physics-notes §4.2): read the fields at the
// star's axis points, Newton-solve for (sigma, C_B) with the TOV sigma-model, reset rho0 by the
// Bernoulli equation with the modelled fields, flood-fill the star. This form is the static
// limit (Omegahat = 0, no black hole, 2-point solve); the binary adds Omega and the third point.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "bhnsid/interfaces/tov_family.hpp"

namespace bhnsid::hydro_corotating {

struct StarSettings {
  double rho_max = 0;        ///< (rho0)_max, a fixed input (physics-notes §3)
  double x_a = -1;           ///< xhat_A, the inner surface point on the x axis; -1: centred star
  double sigma_guess = 0;    ///< initial sigma; 0: R_iso(rho_max) / Rhat (physics-notes §4.7)
  double tolerance = 1e-6;   ///< on |d sigma / sigma| and |d C_B / C_B|
  bool iterate = true;       ///< false: keep the initial TOV density (a fixed-source solve)
};

/// The constants the outer iteration solves for.
struct StarConstants {
  double sigma = 0;
  double bernoulli = 0;  ///< C_B
  double x_c = 0;        ///< xhat_C, the density maximum on the x axis
};

/// The fluid as the field equations see it (the "hydro" service).
class StarFluid final : public Fluid {
 public:
  double sigma() const override { return constants.sigma; }
  bool moving() const override { return false; }
  std::array<double, 3> centre() const override { return {robin_centre, 0.0, 0.0}; }
  double bernoulli_constant() const override { return constants.bernoulli; }
  StarConstants constants;
  double robin_centre = 0;  ///< fixed at the initial xhat_C: the solver reads its boundary once
};

/// What one outer step did, for the log, the CHECK entry and the history file.
struct StepReport {
  int iteration = 0;
  StarConstants before, after;
  double change = 0;  ///< max(|d sigma / sigma|, |d C_B / C_B|)
  bool converged = false;
  int matter_points = 0;
};

class Star {
 public:
  /// Fills `fluid` (published earlier, so the equations could find it) with the initial constants.
  Star(Grid& grid, const Eos& eos, const TovFamily& family, StarSettings settings, std::shared_ptr<StarFluid> fluid);

  /// TOV initial guess (physics-notes §4.7): rho0, chi = psi_TOV, eta = alpha_TOV psi_TOV of the TOV
  /// star of rho_max placed on hatted radius Rhat about xhat_C.
  void set_initial();
  /// One outer step after a field solve; keeps the old density when converged, so that the
  /// written fields and their sources stay a consistent pair.
  StepReport step();

  double rhat_star() const { return 0.5 * (1.0 - settings_.x_a); }
  const std::vector<StepReport>& history() const { return history_; }
  /// star_axis.tsv: x, rho0, chi, eta, alpha and the TOV values at the same physical radius.
  std::string axis_table() const;

 private:
  /// Fills press and enthalpy from rho0 on the finest level.
  void fill_thermodynamics();
  /// rho0 from the Bernoulli equation with the sigma-modelled lapse; returns the matter points.
  int bernoulli_reset(const StarConstants& next);
  double axis_maximum() const;  // xhat_C from the parabola through the axis maximum (§4.3)

  Grid& grid_;
  const Eos& eos_;
  const TovFamily& family_;
  StarSettings settings_;
  TovStar tov_;
  std::shared_ptr<StarFluid> fluid_;
  std::vector<StepReport> history_;
  int rho0_, press_, enthalpy_, chi_, eta_, puncture_phi_;
};

}  // namespace bhnsid::hydro_corotating
