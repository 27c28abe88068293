#pragma once
// The momentum constraint as an EllipticEquation service ("equation.momentum"): unknown W^i
// (field wvec, 3 components, time-odd), Robin falloff W -> 0 about the origin (physics-notes §5.2).
// It also owns Ahat^ij and aa_hat (fill_curvature), which it refreshes around each solve.
#include <string>
#include <vector>

#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "curvature.hpp"
#include "kernels.hpp"

namespace bhnsid::momentum {

/// The weight q of the ansatz Zhat = chi^7/(2 q) (LW): the lapse's regular part (the paper's eta) or 1.
enum class Weight { lapse, unit };

class MomentumEquation final : public EllipticEquation {
 public:
  /// Registers wvec, wvec_weight, ahat and aa_hat (and, with a fluid, the fluid fields); reads chi
  /// and puncture_phi, which must exist already (core::RunFailure naming the missing one). The weight
  /// q is the lapse's regular part (Weight::lapse: `lapse` must be given) or 1. fluid and puncture
  /// may be null (vacuum: no J term; no hole: no Bowen-York term).
  MomentumEquation(Grid& grid, const Lapse* lapse, Weight weight, const Fluid* fluid, const Puncture* puncture,
                   double source_scale);

  std::string name() const override { return "momentum"; }
  std::string unknown() const override { return fields::wvec; }
  OuterBoundary boundary() const override;
  std::vector<std::string> coefficients() const override;
  void residual(const RelaxArgs& args, double* const* out) const override;
  void relax(const RelaxArgs& args) const override;

  /// ahat = Bowen-York + Zhat and aa_hat on every level from the current W, chi, q and puncture;
  /// core::RunFailure naming the point where q is not positive.
  /// Returns how much the finest level's Ahat moved (the consistency check of the loop).
  CurvatureChange fill_curvature() const;

 private:
  Sources sources(int level) const;
  /// wvec_weight on `level` from its source (a copy of the lapse's regular part), ghosts included.
  void refresh_weight(int level) const;

  Grid& grid_;
  const Fluid* fluid_;
  const Puncture* puncture_;
  double source_scale_;
  Weight weight_kind_;
  int w_ = -1, chi_ = -1, weight_ = -1, weight_source_ = -1, puncture_phi_ = -1, ahat_ = -1, aa_ = -1;
};

}  // namespace bhnsid::momentum
