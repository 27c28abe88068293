// eos_polytrope: the paper's equation of state P = K rho0^Gamma, published as the "eos" service.
// A run swaps it for another EOS (eos_piecewise_polytrope) by naming that plugin instead.
#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "polytrope.hpp"

namespace bhnsid::eos_polytrope {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::shared_ptr<Polytrope> eos;
};

// The declared ranges already refuse these; the check is repeated so that the message names the
// key even if a range is loosened, and to refuse non-finite values.
void check(const core::ParamSection& p) {
  const double gamma = p.real("gamma"), k = p.real("k");
  if (!(std::isfinite(gamma) && gamma > 1.0))
    throw core::InputError(fmt::format("eos_polytrope.gamma = {}: expected > 1 (Gamma = 1 is isothermal, no polytrope)", gamma));
  if (!(std::isfinite(k) && k > 0.0))
    throw core::InputError(fmt::format("eos_polytrope.k = {}: expected > 0 and finite", k));
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.implements("eos");

  b.real("gamma").doc("adiabatic index Gamma of P = K rho0^Gamma (the paper: 2)").default_value(2.0).greater_than(1.0);
  b.real("k")
      .doc("polytropic constant K (the paper: 1, which fixes the code's length unit K^(1/(2(Gamma-1))))")
      .default_value(1.0)
      .greater_than(0.0);

  b.schedule(Bin::paramcheck, "check", [](Context& ctx) { check(ctx.params()); })
      .doc("Gamma > 1 and K > 0, finite (also run by bhnsid check)");

  b.schedule(Bin::startup, "publish", [state](Context& ctx) {
     const auto& p = ctx.params();
     state->eos = std::make_shared<Polytrope>(p.real("gamma"), p.real("k"));
     ctx.publish<Eos>("eos", state->eos);
     ctx.log().info("{}", state->eos->describe());
   }).doc("build the polytrope and publish it as the eos service");
}

}  // namespace
}  // namespace bhnsid::eos_polytrope

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "eos_polytrope", "1.0",
                                     "equation of state: single polytrope P = K rho0^Gamma (service eos)",
                                     &bhnsid::eos_polytrope::declare};
  return &info;
}
