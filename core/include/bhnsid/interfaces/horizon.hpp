#pragma once
// The hole's apparent horizon as others read it ("horizon" capability): its irreducible mass, the
// mass a sequence holds fixed and the binding energy subtracts. Published by the plugin that finds
// it; the value is that of its last search (the final fields in ANALYSIS; with tracking, also the
// last outer iteration's solve).
#include <cmath>

#include "bhnsid/core/services.hpp"

namespace bhnsid {

class ApparentHorizon : public core::Service {
 public:
  ~ApparentHorizon() override;  ///< defined in the core library (see grid.hpp)
  /// M_irr = sqrt(A/16 pi) in hatted units (the physical mass over sigma), NaN before a horizon is found.
  virtual double irreducible_mass_hat() const = 0;
  /// Whether a search follows every outer iteration (so that irreducible_mass_hat() is current in UPDATE).
  virtual bool tracking() const = 0;
};

}  // namespace bhnsid
