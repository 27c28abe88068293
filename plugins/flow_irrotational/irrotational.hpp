#pragma once
// The irrotational flow: h u_a = nabla_a Psi, stored as Psitilde = Psi/(sigma C_B) on the hatted
// grid (no sigma and no C_B in its equation). With p = C_B dhat Psitilde (= d_i Psi):
//   W = sqrt(1 + phi^-4 |p|^2 / h^2)                (the normalisation, inside the field solve)
//   v^i = phi^-4 p_i / (h W)                        (Eulerian, Valencia)
//   j^i = rho0 W phi^-4 p_i,  rho_E = rho0 h W^2 - P,  S = rho0 h (W^2 - 1) + 3 P
//   first integral: h alpha W - B^i p_i = C_B,  i.e.  h = C_B G,
//   G^2 = ((1 + B^i dhat_i Psitilde)/alpha)^2 - phi^-4 |dhat Psitilde|^2,  B = beta + Omegahat xi,
// and Psitilde from rest-mass conservation (potential.hpp), solved at the start of each outer step.
#include <array>
#include <string>
#include <vector>

#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/flow.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "potential.hpp"

namespace bhnsid::flow_irrotational {

inline constexpr const char* potential_field = "psi_tilde";

class Irrotational final : public Flow {
 public:
  /// `corotating_start`: outer steps of a cold start (Psitilde 0 everywhere) taken with the
  /// corotating flow before the potential is first solved (corotating_start.hpp).
  Irrotational(PotentialSettings settings, int corotating_start)
      : settings_(settings), corotating_start_(corotating_start) {}
  /// The lapse and the EOS the flow reads, and the field Psitilde registered on `grid`.
  void attach(Grid& grid, const Lapse& lapse, const Eos& eos);

  std::string kind() const override { return "irrotational"; }
  std::vector<std::string> source_inputs() const override { return {potential_field}; }
  double prepare(Grid& grid, const FlowConstants& c) override;
  void set_constants(Grid& grid, const FlowConstants& c) override;
  void update_sources(Grid& grid, int level, const FlowConstants& c) const override;
  void velocity(Grid& grid, const FlowConstants& c, double* lorentz, double* const* v) const override;
  std::string acausal_matter(Grid&, const FlowConstants&) const override { return {}; }
  void enthalpy(Grid& grid, const FlowConstants& c, const double* alpha, const double* phi, double* h) const override;
  void first_integral(Grid& grid, const FlowConstants& c, double* out) const override;
  bool solves_continuity() const override { return true; }
  /// The potential's scaling model (q, beta ∝ Omegahat) holds near the Omegahat it was solved at.
  double omega_step_limit() const override { return corotating_ ? 0.0 : 0.2; }
  void freeze_axis(Grid& grid, const std::vector<double>& xs, const FlowConstants& c) override;
  AxisResidual axis_residual(std::size_t p, double alpha, double phi, double omega_hat, double bernoulli,
                             double enthalpy) const override;

  /// True while a cold start's first outer steps take the corotating flow (decided at the first
  /// call: Psitilde 0 everywhere and `corotating_start` > 0).
  bool corotating(Grid& grid) const;
  /// Outer steps begun (prepare calls).
  int outer_steps() const { return prepared_; }

  /// The last potential solve, for the log and the summary.
  const PotentialSolve& last_solve() const { return last_; }
  /// max |Psitilde - Psitilde(centre)| over the star's matter points (0 for a star at rest in a
  /// rotating frame, up to the discretisation), max |dhat Psitilde| there, and the rms of Psitilde
  /// weighted by rho0 (the norm in which the surface's low-order error counts by its mass).
  std::array<double, 3> potential_size(Grid& grid) const;

 private:
  const Lapse& lapse() const;
  /// The vertices the last solve extended from (null before the first): the velocity stencils.
  const std::uint8_t* solved_mask(const Level& lv) const;
  /// The relative change of Psitilde in the star below which the star counts as settled.
  static constexpr double settle_change = 1e-2;
  PotentialSettings settings_;
  int corotating_start_ = 0;
  int prepared_ = 0;
  double relaxation_ = 1.0;  ///< the fraction the last solve took (settings_.relaxation but after a corotating start)
  mutable bool decided_ = false, corotating_ = false;
  const Lapse* lapse_ = nullptr;
  const Eos* eos_ = nullptr;
  int psi_ = -1;
  PotentialSolve last_;
  /// h = C_B G of the star's last reset (finest level): the level set of the next potential solve.
  mutable std::vector<double> reset_enthalpy_;
  /// The rotation's part of Psitilde per unit Omegahat (finest level), from the last solve.
  std::vector<double> psi_xi_;
  /// The axis points of the Newton solve: x, beta^y and dhat_y Psitilde there, and the Omegahat of
  /// the potential then.
  std::vector<double> axis_x_, axis_beta_y_, axis_p_;
  double axis_omega_ = 0;
  double psi_omega_ = 0;  ///< the Omegahat psi_tilde belongs to now (solved with, or scaled to)
  /// The last solve's system and extension sources, and those held since the star settled.
  std::vector<std::uint8_t> source_, held_system_, held_source_;
};

}  // namespace bhnsid::flow_irrotational
