#pragma once
// The Hamiltonian constraint as an EllipticEquation service ("equation.hamiltonian"): unknown chi,
// Robin falloff chi -> 1 about the fluid's centre (or the puncture, or the origin).
#include <string>
#include <vector>

#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "kernels.hpp"

namespace bhnsid::hamiltonian {

class HamiltonianEquation final : public EllipticEquation {
 public:
  /// Registers chi, puncture_phi and aa_hat; fluid and puncture may be null (vacuum, no hole).
  HamiltonianEquation(Grid& grid, const Fluid* fluid, const Puncture* puncture, double matter_scale);

  std::string name() const override { return "hamiltonian"; }
  std::string unknown() const override { return fields::chi; }
  OuterBoundary boundary() const override;
  std::vector<std::string> coefficients() const override;
  std::string failure_hint() const override;
  void residual(const RelaxArgs& args, double* const* out) const override;
  void relax(const RelaxArgs& args) const override;

  /// Fills puncture_phi = Mhat/(2 |x - xhat_BH|) on every level from the current puncture (the
  /// analytic part is exact on every level, never restricted); throws if a point sits on the hole.
  void update_puncture();

 private:
  Sources sources(int level) const;

  Grid& grid_;
  const Fluid* fluid_;
  const Puncture* puncture_;
  double matter_scale_;
  int chi_, puncture_phi_, aa_;
};

}  // namespace bhnsid::hamiltonian
