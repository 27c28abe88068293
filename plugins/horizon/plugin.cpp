// The horizon plugin (implements "horizon"): the apparent horizon about the puncture, its area and
// irreducible mass M_irr = sqrt(A/16 pi), coordinate radii and quasi-local spin (finder.hpp), in
// ANALYSIS and, on request, after every outer iteration's solve. No horizon found is a RunFailure
// naming why: the mass the user asked for is never a guess.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/horizon.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "finder.hpp"

namespace bhnsid::horizon {
namespace {

using core::Bin;
using core::Context;

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

Horizon locate(Context& ctx, State& state) {
  const auto& grid = ctx.services().get<Grid>("grid");
  const auto& puncture = ctx.services().get<Puncture>("puncture");
  const auto* fluid = ctx.services().find<Fluid>("hydro");
  Hole hole{puncture.bare_mass(), puncture.position(), puncture.momentum()};
  FinderSettings s;
  s.l_max = static_cast<int>(ctx.params().integer("l_max"));
  s.equatorial = grid.symmetry() == Symmetry::equatorial;
  s.tolerance = ctx.params().real("tolerance");
  s.max_iterations = static_cast<int>(ctx.params().integer("max_iterations"));
  s.initial_radius = ctx.params().real("initial_radius");
  const double r0 = s.initial_radius > 0 ? s.initial_radius : 0.5 * hole.mass;
  // Start from the last horizon when there is one (the outer iteration moves it little, and by the
  // bare mass's ratio: scaled with it), else from the sphere r0.
  if (state.last && state.last->found && state.basis && state.basis->l_max() == s.l_max && state.last_mass > 0) {
    s.start = state.last->coefficients;
    for (double& c : s.start) c *= hole.mass / state.last_mass;
  }
  double half = ctx.params().real("search_radius");
  if (!(half > 0)) half = 2.0 * r0;
  const int ahat = grid.has_field(fields::ahat) ? grid.field_id(fields::ahat) : -1;
  const LocalFields local(grid, grid.field_id(fields::chi), ahat, hole, half);
  if (!state.basis || state.basis->l_max() != s.l_max) state.basis.emplace(s.l_max, s.equatorial);
  Horizon h = find_horizon(local, *state.basis, s);
  state.sigma = fluid ? fluid->sigma() : 1.0;
  state.centre = hole.position;
  if (h.found) state.last_mass = hole.mass;
  state.service->mass_hat = h.found ? std::sqrt(h.area_hat / (16 * std::numbers::pi)) : std::nan("");
  if (!h.found)
    throw core::RunFailure(fmt::format(
        "horizon: no apparent horizon found about the puncture (Mhat_BH = {:.6g}, started from the sphere r = {:.4g}, "
        "sampled to r = {:.4g} hatted): {} (horizon.initial_radius, horizon.search_radius, horizon.max_iterations)",
        hole.mass, r0, half, h.failure));
  return h;
}

void report(Context& ctx, const State& state) {
  const Horizon& h = *state.last;
  const double s = state.sigma, area = s * s * h.area_hat;
  ctx.set_scalar("bh_horizon_area", area);
  ctx.set_scalar("bh_irreducible_mass", std::sqrt(area / (16 * std::numbers::pi)));
  ctx.set_scalar("bh_horizon_radius_min", s * h.radius_min);
  ctx.set_scalar("bh_horizon_radius_max", s * h.radius_max);
  ctx.set_scalar("bh_horizon_radius_mean", s * h.radius_mean);
  ctx.set_scalar("bh_horizon_spin", s * s * h.spin_hat);
  ctx.set_scalar("bh_horizon_residual", h.residual);
  ctx.set_scalar("bh_horizon_iterations", h.iterations);
  // The l = 1 part of the coordinate shape about the puncture: a hole moving along y is pushed
  // against its momentum, h ~ M/2 - (P/16) cos(angle to P) at first order.
  ctx.set_scalar("bh_horizon_shift_x", s * h.offset[0]);
  ctx.set_scalar("bh_horizon_shift_y", s * h.offset[1]);
}

/// horizon.tsv: the surface in the planes z = 0 and y = 0 through the puncture (physical), for plots.
std::string surface_table(const State& state) {
  const Horizon& h = *state.last;
  const SurfaceBasis& b = *state.basis;
  std::string out = fmt::format(
      "# apparent horizon, M_irr = {:.12g}, puncture = ({:.12e} {:.12e} {:.12e}); plane, angle, x, y, z (physical)\n",
      state.sigma * std::sqrt(h.area_hat / (16 * std::numbers::pi)), state.sigma * state.centre[0],
      state.sigma * state.centre[1], state.sigma * state.centre[2]);
  const int n = 360;
  for (int plane = 0; plane < 2; ++plane)
    for (int k = 0; k <= n; ++k) {
      const double t = 2 * std::numbers::pi * k / n;
      // z = 0: theta = pi/2, phi = t; y = 0: the meridian phi = 0 / pi.
      const double theta = plane == 0 ? 0.5 * std::numbers::pi : std::acos(std::cos(t));
      const double phi = plane == 0 ? t : (std::sin(t) >= 0 ? 0.0 : std::numbers::pi);
      const double r = b.radius(h.coefficients, theta, phi);
      const double x = state.centre[0] + r * std::sin(theta) * std::cos(phi);
      const double y = state.centre[1] + r * std::sin(theta) * std::sin(phi);
      const double z = state.centre[2] + r * std::cos(theta);
      out += fmt::format("{}\t{:.6f}\t{:.12e}\t{:.12e}\t{:.12e}\n", plane == 0 ? "z=0" : "y=0", t, state.sigma * x,
                         state.sigma * y, state.sigma * z);
    }
  return out;
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("grid");
  b.require("puncture");
  b.require("equation.hamiltonian");
  b.implements("horizon");
  b.integer("l_max").doc("the surface's spherical harmonics up to this degree").default_value(std::int64_t{8}).at_least(2).at_most(24);
  b.real("tolerance")
      .doc("Newton stops when the largest coefficient step is below this times the mean radius")
      .default_value(1e-10)
      .greater_than(0)
      .at_most(1e-2);
  b.integer("max_iterations").doc("Newton steps before the search is declared failed").default_value(std::int64_t{40}).at_least(1);
  b.real("initial_radius")
      .doc("radius of the starting sphere about the puncture (hatted); 0: Mhat_BH/2, the Schwarzschild horizon")
      .default_value(0.0)
      .at_least(0);
  b.real("search_radius")
      .doc("half-width of the box about the puncture whose fields the search samples (hatted); 0: twice the starting "
           "radius; the surface must stay inside it")
      .default_value(0.0)
      .at_least(0);
  b.boolean("every_iteration")
      .doc("also find the horizon after every outer iteration's solve (progress shows bh_irreducible_mass)")
      .default_value(false);

  b.schedule(Bin::setup, "publish", [state](Context& ctx) {
     state->service->track = ctx.params().boolean("every_iteration");
     ctx.publish<ApparentHorizon>("horizon", state->service);
   }).doc("publish the horizon service (M_irr of the last search)");

  b.schedule(Bin::update, "track", [state](Context& ctx) {
     if (!ctx.params().boolean("every_iteration")) return;
     state->last = locate(ctx, *state);
     ctx.show_progress("bh_irreducible_mass", state->sigma * std::sqrt(state->last->area_hat / (16 * std::numbers::pi)));
   })
      .before_if_present("puncture.binary_update")
      .doc("with every_iteration: the horizon of the last solve, before the hole is moved");

  b.schedule(Bin::analysis, "find", [state](Context& ctx) {
     try {
       state->last = locate(ctx, *state);
     } catch (...) {
       state->last.reset();  // no surface of earlier fields in horizon.tsv
       throw;
     }
     report(ctx, *state);
     const Horizon& h = *state->last;
     ctx.log().info("horizon: M_irr = {:.9g}, area {:.9g}, coordinate radius {:.6g} .. {:.6g} (mean {:.6g}), spin {:.3e}; "
                    "{} Newton steps, max |phi^2 Theta| r = {:.2e}",
                    state->sigma * std::sqrt(h.area_hat / (16 * std::numbers::pi)), state->sigma * state->sigma * h.area_hat,
                    state->sigma * h.radius_min, state->sigma * h.radius_max, state->sigma * h.radius_mean,
                    state->sigma * state->sigma * h.spin_hat, h.iterations, h.residual);
   }).doc("the apparent horizon of the final fields: bh_horizon_area, bh_irreducible_mass, bh_horizon_radius_min/_max/_mean, "
          "bh_horizon_spin, bh_horizon_residual, bh_horizon_iterations, bh_horizon_shift_x/_y (the l = 1 part of the shape; physical)");

  b.schedule(Bin::output, "surface", [state](Context& ctx) {
     if (state->last) ctx.write_output("horizon.tsv", surface_table(*state));
   }).doc("horizon.tsv: the surface in the planes z = 0 and y = 0 (physical), when one was found");
}

}  // namespace
}  // namespace bhnsid::horizon

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "horizon", "1.0",
                                     "the apparent horizon about the puncture: area, irreducible mass, radii, spin",
                                     &bhnsid::horizon::declare};
  return &info;
}
