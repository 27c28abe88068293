#pragma once
// The lapse as its readers see it ("lapse" capability). The shift, the fluid, the IRE, the
// diagnostics and the output read alpha only through this service: which unknown a lapse plugin
// relaxes (eta = alpha phi, a regular part of it, a constant) and how alpha follows from it is that
// plugin's business, so another slicing is swapped in by the parameter file alone.
//
// alpha may be negative: a lapse with the static Schwarzschild limit crosses 0 on the hole's
// horizon and is negative on the solved points just outside the excision cube. A reader never
// divides by alpha where it may vanish (only inside the matter, where it is positive, and it checks).
#include <string>

#include "bhnsid/core/services.hpp"
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid {

namespace fields {
/// lapse: alpha on every level, refreshed by Lapse::update (registered by the plugin implementing "lapse").
inline constexpr const char* alpha = "alpha";
}  // namespace fields

class Lapse : public core::Service {
 public:
  ~Lapse() override;  ///< defined in the core library (see grid.hpp)
  /// Fills fields::alpha at every stored point and symmetry ghost of `level` from the current
  /// unknowns of that level. A reader calls it once per sweep before it reads the level's alpha
  /// (the unknowns change between sweeps), as it calls Fluid::update_sources.
  virtual void update(Grid& grid, int level) const = 0;
  /// A grid field (every level) that is positive everywhere, regular at the puncture and equal to
  /// alpha phi up to the puncture's own term: the momentum equation's default weight (its
  /// vector-potential ansatz takes any positive weight: plugins/momentum/README.md).
  virtual std::string regular_part() const = 0;
};

/// Refreshes and returns alpha on `level` (ghosts on symmetry planes filled).
inline const double* lapse_on(Grid& grid, const Lapse& lapse, int level) {
  lapse.update(grid, level);
  return grid.data(grid.field_id(fields::alpha), 0, level);
}

}  // namespace bhnsid
