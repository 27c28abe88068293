#pragma once
// The corotating flow (physics-notes §1.2, §2.1, §3): the fluid is at rest in the frame that rotates
// with Omegahat about the z axis, u^a proportional to the helical Killing vector, so that v^i =
// (beta^i + Omegahat xi^i)/alpha and the first integral is h / u^t = C_B (eq. bernoulli_hat).
#include <string>
#include <vector>

#include "bhnsid/interfaces/flow.hpp"
#include "bhnsid/interfaces/lapse.hpp"

namespace bhnsid::flow_corotating {

class Corotation final : public Flow {
 public:
  /// The lapse the kinematics read (published at SETUP, after this flow).
  void attach(const Lapse& lapse) { lapse_ = &lapse; }

  std::string kind() const override { return "corotating"; }
  void update_sources(Grid& grid, int level, const FlowConstants& c) const override;
  void velocity(Grid& grid, const FlowConstants& c, double* lorentz, double* const* v) const override;
  std::string acausal_matter(Grid& grid, const FlowConstants& c) const override;
  void enthalpy(Grid& grid, const FlowConstants& c, const double* alpha, const double* phi, double* h) const override;
  void first_integral(Grid& grid, const FlowConstants& c, double* out) const override;
  void freeze_axis(Grid& grid, const std::vector<double>& xs, const FlowConstants& c) override;
  AxisResidual axis_residual(std::size_t p, double alpha, double phi, double omega_hat, double bernoulli,
                             double enthalpy) const override;

 private:
  const Lapse& lapse() const;
  std::vector<double> axis_x_, axis_beta_y_;  ///< the axis points and beta^y there (beta^x = beta^z = 0 by symmetry)
  const Lapse* lapse_ = nullptr;
};

}  // namespace bhnsid::flow_corotating
