#pragma once
// The star of the star plugin: its constants (sigma, C_B, Omegahat, x_C), the fluid fields on the
// grid, and the outer-iteration step (physics-notes §4.2): read the fields at the star's axis points,
// Newton-solve for the constants with the TOV sigma-model and the flow's first integral, reset rho0
// by that first integral with the modelled fields, flood-fill the star. Without a black hole:
// Omegahat held (0, or a test's value) and the 2-point solve for (sigma, C_B) (physics-notes §9 T1).
// With one (a puncture service): the 3-point solve for (sigma, Omegahat, C_B) at xhat = 1, xhat_A,
// xhat_C, the model evaluated at sigma_eff = sigma (1 + delta)^2, delta = Mhat_BH/(2 dhat) (§4.5).
// How the fluid moves (W, v, the first integral) is the flow's (Flow): one star for every flow.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/core/checkpoint.hpp"
#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/flow.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "bhnsid/interfaces/tov_family.hpp"
#include "fluid.hpp"

namespace bhnsid::star {

struct StarSettings {
  double rho_max = 0;        ///< (rho0)_max, a fixed input (physics-notes §3)
  double x_a = -1;           ///< xhat_A, the inner surface point on the x axis; -1: centred star
  double sigma_guess = 0;    ///< initial sigma; 0: R_iso(rho_max) / Rhat (physics-notes §4.7)
  double model_hole_delta = 1;  ///< the sigma-model's initial share of the hole's delta (delta_weight_)
  double tolerance = 1e-6;   ///< on |d sigma / sigma| and |d C_B / C_B|
  bool iterate = true;       ///< false: keep the initial TOV density (a fixed-source solve)
  double test_omega_hat = 0; ///< Omegahat of a single star (no hole), held through the run
};

/// What one outer step did, for the log, the CHECK entry and the history file.
struct StepReport {
  int iteration = 0;
  StarConstants before, after;
  double change = 0;  ///< max(|d sigma / sigma|, |d Omegahat / Omegahat|, |d C_B / C_B|, |d M0 / M0|)
  bool converged = false;
  int matter_points = 0;
  double fraction = 1;         ///< of the Newton step taken (1/2^m after m retreats)
  double rest_mass_before = 0;  ///< M0 before the reset, and the change of M0 before it, for retreat()
  double m0_change_before = 1;
  std::string model_note;  ///< why this step's sigma-model took less of the hole's delta (empty: as before)
};

class Star {
 public:
  /// Fills `fluid` (published earlier, so the equations could find it) with the initial constants;
  /// `hole` is the black hole of a binary, or null.
  Star(Grid& grid, const Eos& eos, const TovFamily& family, const Lapse& lapse, Flow& flow, StarSettings settings,
       std::shared_ptr<StarFluid> fluid, const Puncture* hole);

  /// TOV initial guess (physics-notes §4.7): rho0, chi = psi_TOV, the lapse's regular part = alpha_TOV psi_TOV of the TOV
  /// star of rho_max placed on hatted radius Rhat about xhat_C; with a hole, sigma_0 = R_iso/(Rhat
  /// phi_ext^2), phi_ext = 1 + delta (the hole shrinks the star; R_iso/Rhat lies above the fold).
  void set_initial();
  /// One outer step after a field solve; keeps the old density when converged, so that the
  /// written fields and their sources stay a consistent pair. `fraction` < 1 (after a retreat):
  /// sigma, Omegahat and C_B move that fraction of the way from the last constants to the Newton
  /// solution (physics-notes §4.4: "halve (sigma - sigma_old) and retry"), and the step is never
  /// judged converged.
  StepReport step(double fraction = 1);
  /// Undoes the last step's constants (the next step() resets the density again from the restored
  /// fields); throws RunFailure when there is no applied step to undo.
  void retreat();

  /// The constants, the outer steps taken and what the next step and a retreat compare with
  /// (star_checkpoint.cpp); the density itself is a grid field, saved by the grid.
  void save(core::CheckpointWriter& out) const;
  void restore(const core::CheckpointReader& in);
  /// From a neighbour's checkpoint (another rho_max): its sigma, C_B, Omegahat and xhat_C as the start
  /// of the outer iteration; the star's target (rho_max, M0) and convergence history stay this run's.
  void warm_start(const core::CheckpointReader& in);

  double rhat_star() const { return 0.5 * (1.0 - settings_.x_a); }
  const std::vector<StepReport>& history() const { return history_; }
  /// star_axis.tsv: x, rho0, chi, the lapse's regular part, alpha and the TOV values at the same physical radius.
  std::string axis_table() const;

 private:
  /// Fills press and enthalpy from rho0 on the finest level.
  void fill_thermodynamics();
  /// rho0 from the Bernoulli equation with the sigma-modelled lapse and conformal factor, the shift
  /// and Omegahat, from the last solve's alpha and phi (finest level, ghosts filled); returns the
  /// matter points.
  int bernoulli_reset(const StarConstants& next, const std::vector<double>& alpha, const std::vector<double>& phi);
  /// delta = Mhat_BH/(2 dhat), the hole's conformal factor across the star (0 without a hole).
  double hole_delta() const;
  /// The model's sigma: sigma (1 + w delta)^2 (physics-notes §4.5, "with a black hole present"),
  /// w = delta_weight_.
  double model_sigma(double sigma) const;
  /// Omegahat from Kepler, sqrt(Mhat_tot / dhat^3) (hatted; physics-notes §4.7).
  double kepler_omega() const;
  double axis_maximum() const;  // xhat_C from the parabola through the axis maximum (§4.3)

  Grid& grid_;
  const Eos& eos_;
  const TovFamily& family_;
  const Lapse& lapse_;
  StarSettings settings_;
  TovStar tov_;
  std::shared_ptr<StarFluid> fluid_;
  const Puncture* hole_;
  double m0_change_ = 1;  ///< |d M0 / M0| of the last reset
  /// How much of the hole's delta the sigma-model takes: 1, halved (then 0) each time the corotating
  /// Newton solve fails with it. The model only shapes the path (at the fixed point its change
  /// vanishes), and delta = Mhat/(2 dhat) of a close hole can put sigma (1 + delta)^2 over the
  /// frozen-profile fold while the star itself is below it.
  double delta_weight_ = 1;
  double undone_rest_mass_ = 0;  ///< M0 before the step retreat() undid (0: none), for the next step
  std::vector<StepReport> history_;
  int rho0_, press_, enthalpy_, chi_, lapse_regular_, puncture_phi_;
};

}  // namespace bhnsid::star
