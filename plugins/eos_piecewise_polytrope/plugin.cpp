// eos_piecewise_polytrope: the Read et al. (2009) piecewise polytrope (SLy crust + three core pieces),
// published as the "eos" service; a run swaps it for eos_polytrope by naming this plugin instead.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <utility>
#include <stdexcept>
#include <string>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "piecewise_polytrope.hpp"
#include "units.hpp"

namespace bhnsid::eos_piecewise_polytrope {
namespace {

using core::Bin;
using core::Context;

// The custom parameters default to the SLy fit, so that the defaults describe one star whatever the preset.
constexpr CoreParams custom_default{34.384, 3.005, 2.988, 2.851};

struct State {
  std::shared_ptr<PiecewisePolytrope> eos;
};

// The EOS the parameters describe; every mistake is an InputError naming the key.
std::shared_ptr<PiecewisePolytrope> build(const core::ParamSection& p) {
  const std::string& preset = p.string("preset");
  const CoreParams given{p.real("log10_p1"), p.real("gamma1"), p.real("gamma2"), p.real("gamma3")};
  CoreParams core = given;
  std::string label = "custom";
  if (preset != "custom") {
    const auto found = find_preset(preset);
    if (!found)  // the keyword list refuses this first; kept for a preset added to the list but not to the table
      throw core::InputError(fmt::format("eos_piecewise_polytrope.preset = {}: unknown preset", preset));
    // A custom value set beside a named preset would be silently ignored: refuse it.
    const std::pair<const char*, double> keys[] = {{"log10_p1", given.log10_p1 - custom_default.log10_p1},
                                                   {"gamma1", given.gamma1 - custom_default.gamma1},
                                                   {"gamma2", given.gamma2 - custom_default.gamma2},
                                                   {"gamma3", given.gamma3 - custom_default.gamma3}};
    for (const auto& [key, diff] : keys)
      if (diff != 0.0)
        throw core::InputError(fmt::format(
            "eos_piecewise_polytrope.{} = {}: only used with preset: custom, but preset = {}; remove it or set "
            "preset: custom",
            key, p.real(key), preset));
    core = *found;
    for (const Preset& q : presets())
      if (preset == q.name) label = q.label;
  }
  // The declared ranges refuse these already; repeated here so that the message names the key for
  // any value the ranges let through (non-finite ones).
  const std::pair<const char*, double> gammas[] = {{"gamma1", core.gamma1}, {"gamma2", core.gamma2}, {"gamma3", core.gamma3}};
  for (const auto& [key, value] : gammas)
    if (!(std::isfinite(value) && value > 1.0))
      throw core::InputError(fmt::format("eos_piecewise_polytrope.{} = {}: expected > 1", key, value));
  try {
    return std::make_shared<PiecewisePolytrope>(core, label);
  } catch (const std::invalid_argument& e) {  // what is left: log10_p1 and gamma1 place the junction wrongly
    throw core::InputError(fmt::format("eos_piecewise_polytrope.log10_p1 = {} (preset {}, gamma1 = {}): {}",
                                       core.log10_p1, preset, core.gamma1, e.what()));
  }
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.implements("eos");

  b.keyword("preset", {"custom", "sly", "apr4", "h4", "ms1"})
      .doc("fit of Read et al. 2009 Table III, or custom: log10_p1 and gamma1..3 below")
      .default_value(std::string("sly"));
  b.real("log10_p1")
      .doc("custom only: log10 of the pressure (dyn/cm^2) at rho1 = 10^14.7 g/cm^3")
      .default_value(custom_default.log10_p1);
  b.real("gamma1")
      .doc("custom only: adiabatic index between the crust and rho1 = 10^14.7 g/cm^3")
      .default_value(custom_default.gamma1)
      .greater_than(1.0);
  b.real("gamma2")
      .doc("custom only: adiabatic index between 10^14.7 and 10^15 g/cm^3")
      .default_value(custom_default.gamma2)
      .greater_than(1.0);
  b.real("gamma3").doc("custom only: adiabatic index above 10^15 g/cm^3").default_value(custom_default.gamma3).greater_than(1.0);

  b.schedule(Bin::paramcheck, "check", [](Context& ctx) { build(ctx.params()); })
      .doc("the preset or custom pieces give a valid EOS (also run by bhnsid check)");

  b.schedule(Bin::startup, "publish", [state](Context& ctx) {
     state->eos = build(ctx.params());
     ctx.publish<Eos>("eos", state->eos);
     ctx.log().info("{}", state->eos->describe());
     ctx.log().info("units: length {:.6f} km, density {:.5e} g/cm^3, pressure {:.5e} dyn/cm^2",
                    units::length_cm * 1e-5, units::density_g_cm3, units::pressure_dyn_cm2);
   }).doc("build the piecewise polytrope and publish it as the eos service");
}

}  // namespace
}  // namespace bhnsid::eos_piecewise_polytrope

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "eos_piecewise_polytrope", "1.0",
                                     "equation of state: Read et al. 2009 piecewise polytrope, SLy crust (service eos)",
                                     &bhnsid::eos_piecewise_polytrope::declare};
  return &info;
}
