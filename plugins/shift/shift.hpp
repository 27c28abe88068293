#pragma once
// The minimal-distortion shift as an EllipticEquation service ("equation.shift"): unknown beta^i,
// Robin falloff beta -> 0 about the origin (physics-notes §5.2), Dirichlet beta_0 in the excision
// cube about the puncture (§4.6).
#include <array>
#include <optional>
#include <cstdint>
#include <string>
#include <vector>

#include "bhnsid/core/checkpoint.hpp"
#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "excision.hpp"
#include "kernels.hpp"

namespace bhnsid::shift {

struct Settings {
  ExcisionValue excision_value = ExcisionValue::lorentz;
  double source_scale = 1;  ///< TEST ONLY factor on the Ahat term
  double coupling_scale = 1;  ///< TEST ONLY factor on the (6/phi)(d beta) d phi term
  double min_side = 0;      ///< smallest full side of the excision cube (hatted); 0: max(M/2, 3 dx) alone
  double lattice = 0;       ///< > 0: faces of the excision cube on the planes of this lattice (snap_to_lattice)
  int local_sweeps = 16;    ///< extra red-black sweeps on the box about the hole after every sweep
  int local_width = 8;      ///< the box: the held points' bounding box widened by this many points
  int local_levels = 2;     ///< the finest levels with local_sweeps; the coarser get coarse_local_sweeps
  int coarse_local_sweeps = 4;
};

/// What one refresh of the puncture terms did, for the log and the scalars.
struct ExcisionReport {
  bool changed = false;            ///< the mask was rebuilt
  bool coarsest_changed = false;   ///< the coarsest level's held points differ from the last build
  int finest_points = 0;           ///< excised stored points of the finest level
  std::vector<int> nearest_levels; ///< levels where the cube holds no point (nearest point held)
  Cube cube;
  std::array<double, 3> beta0{};
};

class ShiftEquation final : public EllipticEquation {
 public:
  /// Registers beta (and, with a puncture, the excision mask); reads chi, ahat and the lapse, which other
  /// plugins provide: core::InputError naming the missing field or service otherwise. With a
  /// puncture: InputError for Mhat_BH <= 0, |v| >= 1 or a cube reaching the outer boundary. fluid
  /// and puncture may be null (vacuum, no hole).
  ShiftEquation(Grid& grid, const Lapse* lapse, const Fluid* fluid, const Puncture* puncture, Settings settings);

  std::string name() const override { return "shift"; }
  std::string unknown() const override { return fields::shift; }
  OuterBoundary boundary() const override;
  std::string excision_mask() const override { return puncture_ ? fields::excision_mask : std::string{}; }
  std::vector<std::string> coefficients() const override;
  void residual(const RelaxArgs& args, double* const* out) const override;
  void relax(const RelaxArgs& args) const override;

  /// Before every solve: when the puncture changed, rebuild the excision mask on every level; then
  /// set beta = beta_0 at every excised point of every level. core::RunFailure for a puncture that
  /// became invalid (the cube reaching the boundary, Mhat <= 0, |v| >= 1). Without a puncture it
  /// does nothing.
  ExcisionReport update_puncture();
  /// The puncture the mask was last built for and the boxes of its held points (the mask itself is
  /// the grid's, saved there), so that a resumed run neither logs a move that did not happen nor
  /// loses the held region of its output (shift_checkpoint.cpp).
  void save(core::CheckpointWriter& out) const;
  void restore(const core::CheckpointReader& in);
  /// `bhnsid run --warm-start`: restore() from a run of this lattice; from a coarser one (whose
  /// masks the grid does not carry over) the excision SETUP built here stays.
  void warm_start(const core::CheckpointReader& in);
  /// The cube the excision mask was last built for (hatted), none before the first build or
  /// without a puncture.
  std::optional<Cube> held_cube() const {
    if (!puncture_ || !built_) return std::nullopt;
    return excision(last_mass_, last_position_);
  }

 private:
  Sources sources(int level) const;
  /// Throws E (InputError at SETUP, RunFailure later) when the puncture cannot be excised.
  /// The excision cube of the hole: excision_cube, snapped to the lattice when settings say so.
  Cube excision(double mass, const std::array<double, 3>& position) const;
  template <class E>
  void check_puncture(double mass, const std::array<double, 3>& position, const std::array<double, 3>& momentum) const;

  Grid& grid_;
  const Lapse* lapse_;
  const Fluid* fluid_;
  const Puncture* puncture_;
  Settings settings_;
  int beta_ = -1, chi_ = -1, ahat_ = -1;
  int mask_ = -1;
  // The puncture the mask was last built for.
  bool built_ = false;
  double last_mass_ = 0;
  std::array<double, 3> last_position_{};
  int last_finest_points_ = 0;
  /// Per level: the held points' bounding box widened by local_width (inclusive); empty without a hole.
  std::vector<stencil::Box> held_box_;
  std::vector<int> last_nearest_levels_;
};

}  // namespace bhnsid::shift
