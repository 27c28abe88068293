// The tov plugin: static spherical stars (TOV solutions) of the published EOS in isotropic
// coordinates. It publishes the TovFamily service ("tov_family") in SETUP and, in ANALYSIS, reports
// the star of central density tov.central_density (and, on request, the maximum-mass stars).
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "family.hpp"
#include "solver.hpp"

namespace bhnsid::tov {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::shared_ptr<Family> family;
  std::optional<TovStar> star;
};

/// The star of tov.central_density as summary scalars, with an error estimate from a 100 times
/// tighter integration.
void report_star(Context& ctx, State& state) {
  const auto& p = ctx.params();
  const TovStar s = state.family->star(p.real("central_density"));
  state.star = s;
  ctx.set_scalar("adm_mass", s.adm_mass);
  ctx.set_scalar("rest_mass", s.rest_mass);
  ctx.set_scalar("radius_areal", s.radius_areal);
  ctx.set_scalar("radius_isotropic", s.radius_isotropic);
  ctx.set_scalar("lapse_center", s.lapse_center);
  ctx.set_scalar("psi_center", s.psi_center);
  // Error estimate: the same star at a 100 times tighter tolerance.
  Settings tight;
  tight.tolerance = p.real("tolerance") * 1e-2;
  tight.min_steps = static_cast<int>(p.integer("min_steps"));
  const TovStar ref = solve_star(ctx.services().get<Eos>("eos"), s.central_density, tight);
  const double err = std::max(std::fabs(s.adm_mass - ref.adm_mass) / ref.adm_mass,
                              std::fabs(s.rest_mass - ref.rest_mass) / ref.rest_mass);
  ctx.set_scalar("tov_mass_error_estimate", err);
  ctx.log().info("rho0_c = {:.9g}: M = {:.12g}, M0 = {:.12g}, R = {:.12g}, R_iso = {:.12g}, alpha_c = {:.12g}, "
                 "psi_c = {:.12g} (relative mass error ~ {:.1e})",
                 s.central_density, s.adm_mass, s.rest_mass, s.radius_areal, s.radius_isotropic, s.lapse_center,
                 s.psi_center, err);
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("eos");
  b.implements("tov_family");

  b.real("central_density")
      .doc("central rest-mass density rho0_c of a star to report in summary.json (code units of the EOS); 0: none, "
           "the plugin only serves the TOV family to others (a static star's own masses come from diagnostics)")
      .default_value(0.0)
      .at_least(0);
  b.real("tolerance")
      .doc("relative local error tolerance of the adaptive Dormand-Prince 5(4) steps in s = sqrt(ln h_c - ln h)")
      .default_value(1e-12)
      .greater_than(0)
      .at_most(1e-3);
  b.integer("min_steps")
      .doc("the step in s is at most s_surface / min_steps, so the profile has at least min_steps + 2 points")
      .default_value(std::int64_t{256})
      .at_least(1);
  b.boolean("report_maximum")
      .doc("also find the maximum-ADM-mass and maximum-rest-mass stars and report them as scalars")
      .default_value(false);
  b.real("search_density_min")
      .doc("smallest central density of the log scan that brackets the maximum-mass stars")
      .default_value(1e-3)
      .greater_than(0);
  b.real("search_density_max")
      .doc("largest central density of the log scan that brackets the maximum-mass stars")
      .default_value(3.0)
      .greater_than(0);
  b.integer("frozen_profile_points")
      .doc("grid intervals on [0, rhat_star] of the frozen-profile sigma model (physics-notes 4.5; fourth order)")
      .default_value(std::int64_t{400})
      .at_least(8);
  b.real("frozen_profile_step")
      .doc("largest continuation step in sigma of the frozen-profile model, relative to sigma")
      .default_value(0.005)
      .greater_than(0)
      .at_most(0.1);
  b.integer("profile_exterior_points")
      .doc("points of the exterior Schwarzschild solution appended to tov_profile.tsv (0: the interior only)")
      .default_value(std::int64_t{64})
      .at_least(0);
  b.real("profile_outer_radius")
      .doc("the exterior points of tov_profile.tsv reach this multiple of the isotropic radius")
      .default_value(4.0)
      .greater_than(1);

  b.schedule(Bin::paramcheck, "check_search", [](Context& ctx) {
     const auto& p = ctx.params();
     if (!(p.real("search_density_min") < p.real("search_density_max")))
       throw core::InputError(fmt::format("tov.search_density_min = {} must be below tov.search_density_max = {}",
                                          p.real("search_density_min"), p.real("search_density_max")));
   }).doc("the maximum search's density range is not empty");

  b.schedule(Bin::setup, "publish_family", [state](Context& ctx) {
     const auto& p = ctx.params();
     const Eos& eos = ctx.services().get<Eos>("eos");
     Settings settings;
     settings.tolerance = p.real("tolerance");
     settings.min_steps = static_cast<int>(p.integer("min_steps"));
     SearchSettings search;
     search.density_min = p.real("search_density_min");
     search.density_max = p.real("search_density_max");
     FrozenSettings frozen;
     frozen.points = static_cast<int>(p.integer("frozen_profile_points"));
     frozen.step = p.real("frozen_profile_step");
     state->family = std::make_shared<Family>(eos, settings, search, frozen);
     ctx.publish<TovFamily>("tov_family", state->family);
     ctx.log().info("TOV family of EOS {}", eos.describe());
   }).doc("publish the TovFamily of the EOS under tov_family");

  b.checkpoint([state](Context&, core::CheckpointWriter& out) { state->family->save(out); },
               [state](Context&, const core::CheckpointReader& in) { state->family->restore(in); });

  b.schedule(Bin::analysis, "star", [state](Context& ctx) {
     const auto& p = ctx.params();
     if (p.real("central_density") > 0) report_star(ctx, *state);
     if (p.boolean("report_maximum")) {
       const TovStar ma = state->family->maximum_mass_star();
       const TovStar mr = state->family->maximum_rest_mass_star();
       ctx.set_scalar("max_adm_mass", ma.adm_mass);
       ctx.set_scalar("max_adm_mass_central_density", ma.central_density);
       ctx.set_scalar("max_rest_mass", mr.rest_mass);
       ctx.set_scalar("max_rest_mass_central_density", mr.central_density);
       ctx.log().info("maximum ADM mass {:.12g} at rho0_c = {:.9g}; maximum rest mass {:.12g} at rho0_c = {:.9g}",
                      ma.adm_mass, ma.central_density, mr.rest_mass, mr.central_density);
     }
   }).doc("the star of tov.central_density if > 0 (and the maximum-mass stars) as scalars");

  b.schedule(Bin::output, "write_profile", [state](Context& ctx) {
     if (!state->star) return;
     ctx.write_output("tov_profile.tsv",
                      profile_table(*state->star, static_cast<int>(ctx.params().integer("profile_exterior_points")),
                                    ctx.params().real("profile_outer_radius")));
   }).doc("tov_profile.tsv: r_iso, r_areal, psi, alpha, rho0 inside the star and the exterior solution beyond");
}

}  // namespace
}  // namespace bhnsid::tov

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tov", "1.0",
                                     "static spherical stars (TOV) of the published EOS, isotropic coordinates",
                                     &bhnsid::tov::declare};
  return &info;
}
