#pragma once
// The horizon plugin's state across a run and what it reports: the last horizon found (the next
// search starts from it), the "horizon" service, the scalars and horizon.tsv.
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "bhnsid/core/context.hpp"
#include "bhnsid/interfaces/horizon.hpp"
#include "finder.hpp"

namespace bhnsid::horizon {

/// The "horizon" service: the last horizon's M_irr (hatted).
class Service final : public ApparentHorizon {
 public:
  double irreducible_mass_hat() const override { return mass_hat; }
  bool tracking() const override { return track; }
  double mass_hat = std::nan("");
  bool track = false;
};

struct State {
  std::shared_ptr<Service> service = std::make_shared<Service>();
  std::optional<Horizon> last;
  double sigma = 1;
  std::array<double, 3> centre{};
  std::optional<SurfaceBasis> basis;
  double last_mass = 0;  ///< Mhat_BH of the last horizon found
};

/// The horizon of the current fields (parameters from the plugin's section); core::RunFailure naming
/// why when none is found.
Horizon locate(core::Context& ctx, State& state);
/// The scalars of state.last (physical units).
void report(core::Context& ctx, const State& state);
/// horizon.tsv: the surface in the planes z = 0 and y = 0 through the puncture (physical), for plots.
std::string surface_table(const State& state);

}  // namespace bhnsid::horizon
