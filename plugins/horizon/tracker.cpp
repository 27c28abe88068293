#include "tracker.hpp"

#include <fmt/format.h>

#include <numbers>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::horizon {

Horizon locate(core::Context& ctx, State& state) {
  const auto& grid = ctx.services().get<Grid>("grid");
  require_single_box(grid, ctx.plugin());
  const auto& puncture = ctx.services().get<Puncture>("puncture");
  const auto* fluid = ctx.services().find<Fluid>("star");
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

void report(core::Context& ctx, const State& state) {
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

}  // namespace bhnsid::horizon
