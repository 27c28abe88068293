#pragma once
// The maximal-slicing condition as an EllipticEquation service ("equation.lapse"): unknown eta,
// Robin falloff eta -> 1 about the same centre as chi (physics-notes §5.2).
#include <string>
#include <vector>

#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "kernels.hpp"

namespace bhnsid::lapse {

class LapseEquation final : public EllipticEquation {
 public:
  /// Registers eta and alpha; reads chi, puncture_phi and aa_hat, which the hamiltonian plugin registers.
  LapseEquation(Grid& grid, const Fluid* fluid, const Puncture* puncture, double matter_scale);

  std::string name() const override { return "lapse"; }
  std::string unknown() const override { return fields::eta; }
  OuterBoundary boundary() const override;
  std::vector<std::string> coefficients() const override;
  void residual(const RelaxArgs& args, double* const* out) const override;
  void relax(const RelaxArgs& args) const override;

 private:
  Sources sources(int level) const;

  Grid& grid_;
  const Fluid* fluid_;
  const Puncture* puncture_;
  double matter_scale_;
  int eta_;
};

/// The "lapse" service: alpha = eta / phi, phi = Mhat_BH/(2 rhat_BH) + chi. eta is regular and
/// positive, so alpha -> 0 at the puncture and is positive everywhere else.
class EtaLapse final : public Lapse {
 public:
  void update(Grid& grid, int level) const override;
  std::string regular_part() const override { return fields::eta; }
};

}  // namespace bhnsid::lapse
