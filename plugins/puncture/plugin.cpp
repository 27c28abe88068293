// The puncture plugin (implements "puncture"): the black hole as a Brandt-Brugmann puncture of bare
// mass Mhat_BH at xhat_BH with a Bowen-York momentum Phat_BH (physics-notes §1.3, §2.6). It publishes
// the Puncture service that the field equations read: the analytic Mhat/(2 rhat) part of phi
// (hamiltonian), the Bowen-York part of Ahat^ij (momentum), the excision cube (shift). Alone the three
// are parameters; with mass_ratio > 0 and a star (hydro) they are the binary's, set from the star every
// outer iteration (binary.hpp), so that no hydro plugin carries the black hole's bookkeeping.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/horizon.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "binary.hpp"
#include "grid_points.hpp"

namespace bhnsid::puncture {
namespace {

using core::Bin;
using core::Context;

class Hole final : public Puncture {
 public:
  double bare_mass() const override { return mass; }
  std::array<double, 3> position() const override { return x; }
  std::array<double, 3> momentum() const override { return p; }
  double mass = 0;
  std::array<double, 3> x{}, p{};
  /// The values before the last binary update, for RETREAT.
  struct Saved {
    double mass;
    std::array<double, 3> x, p;
  };
  std::optional<Saved> before_update;
  /// M_irr / (mu M_NS) - 1 at the last update with mass_target = irreducible (NaN before one).
  double irreducible_error = std::nan("");
};

std::array<double, 3> vec3(const std::vector<double>& v) { return {v.at(0), v.at(1), v.at(2)}; }

void declare(core::PluginBuilder& b) {
  auto hole = std::make_shared<Hole>();
  b.implements("puncture");
  b.require("grid");  // the position is checked against grid.n and grid.dx

  b.real("mass_ratio")
      .doc("mu_bn = M_BH / M_NS; > 0: the black hole of a binary with the star of the star, its bare mass, "
           "position and momentum set from the star every outer iteration (Mhat_BH = mu_bn M_NS(M0)/sigma, "
           "xhat_BH = -xhat_C/mu_bn, Phat_y = -sigma^2 Int phi^10 j^y; bare_mass and position are then not used); "
           "0: the puncture of bare_mass, position, momentum")
      .default_value(0.0)
      .at_least(0);
  b.keyword("mass_target", {"bare", "irreducible"})
      .doc("with mass_ratio > 0, which mass of the hole is mu_bn M_NS: bare = the bare mass sigma Mhat_BH (the "
           "paper's), irreducible = the apparent horizon's M_irr = sqrt(A/16 pi), Mhat_BH adjusted every outer "
           "iteration (needs the horizon plugin with horizon.every_iteration: true)")
      .default_value(std::string("bare"));
  b.real("mass_tolerance")
      .doc("with mass_target = irreducible, the loop goes on until |M_irr/(mu_bn M_NS) - 1| is at most this")
      .default_value(1e-7)
      .greater_than(0)
      .at_most(0.1);
  b.real("bare_mass")
      .doc("bare mass Mhat_BH of the puncture (hatted units); required (> 0) unless mass_ratio > 0")
      .default_value(0.0)
      .at_least(0);
  b.real_vector("position")
      .doc("hatted position xhat_BH; must not be a grid point of any multigrid level (1/r there); unused with "
           "mass_ratio > 0")
      .default_value(std::vector<double>{0.0075, 0, 0})
      .length(3);
  b.real_vector("momentum")
      .doc("Bowen-York momentum Phat_BH (hatted units); the z component must be 0 with equatorial symmetry")
      .default_value(std::vector<double>{0, 0, 0})
      .length(3);

  b.schedule(Bin::paramcheck, "check", [](Context& ctx) {
     const auto& p = ctx.params();
     const std::array<double, 3> x = vec3(p.real_vector("position")), mom = vec3(p.real_vector("momentum"));
     const bool binary = p.real("mass_ratio") > 0;
     if (!binary && !(p.real("bare_mass") > 0 && std::isfinite(p.real("bare_mass"))))
       throw core::InputError(fmt::format("puncture.bare_mass = {}: expected a finite value > 0 (or puncture.mass_ratio "
                                          "> 0 for the black hole of a binary)",
                                          p.real("bare_mass")));
     if (!binary) check_off_the_points(ctx, x);
     if (!binary && p.string("mass_target") == "irreducible")
       throw core::InputError("puncture.mass_target = irreducible holds the hole of a binary at mu_bn M_NS: set "
                              "puncture.mass_ratio > 0 (or mass_target: bare)");
     const auto& grid = ctx.params("grid");
     if (grid.string("symmetry") == "equatorial" && (x[2] != 0 || mom[2] != 0))
       throw core::InputError(fmt::format("puncture.position / puncture.momentum: z components {} and {} must be 0 with "
                                          "grid.symmetry = equatorial (the hole must lie in, and move along, z = 0)",
                                          x[2], mom[2]));
   }).doc("bare_mass > 0; the position is not a grid point of any level and lies inside the cube");

  b.schedule(Bin::startup, "publish", [hole](Context& ctx) {
     const auto& p = ctx.params();
     hole->mass = p.real("bare_mass");
     hole->x = vec3(p.real_vector("position"));
     hole->p = vec3(p.real_vector("momentum"));
     ctx.publish<Puncture>("puncture", hole);
     ctx.log().info("puncture: Mhat = {}, xhat = ({}, {}, {}), Phat = ({}, {}, {})", hole->mass, hole->x[0], hole->x[1],
                    hole->x[2], hole->p[0], hole->p[1], hole->p[2]);
   }).doc("publish the Puncture service");

  b.schedule(Bin::setup, "binary_start", [hole](Context& ctx) {
     const double mu = ctx.params().real("mass_ratio");
     if (!(mu > 0)) return;
     const auto* fluid = ctx.services().find<Fluid>("star");
     const auto* family = ctx.services().find<TovFamily>("tov_family");
     if (!fluid || !family)
       throw core::InputError(fmt::format("puncture.mass_ratio = {}: the black hole of a binary needs a star: add a "
                                          "hydro plugin and the tov plugin (M_NS(M0)) to plugins",
                                          mu));
     if (ctx.params().string("mass_target") == "irreducible") {
       const auto* horizon = ctx.services().find<ApparentHorizon>("horizon");
       if (!horizon || !horizon->tracking())
         throw core::InputError("puncture.mass_target = irreducible adjusts Mhat_BH to the apparent horizon's mass every "
                                "outer iteration: add the horizon plugin to plugins with horizon.every_iteration: true");
     }
     const auto& grid = ctx.services().get<Grid>("grid");
     require_single_box(grid, ctx.plugin());
     const HoleValues h = scaled_hole(grid, *fluid, *family, mu, fluid->initial_rest_mass());
     hole->mass = h.mass;
     hole->x = h.position;
     if (!h.moved.empty()) ctx.log().info("puncture: {}", h.moved);
     ctx.log().info("puncture of the binary (mu_bn = {}): Mhat_BH = {:.9g}, xhat_BH = {:.9g} from the initial star "
                    "(M0 = {:.9g}, sigma = {:.9g})",
                    mu, hole->mass, hole->x[0], fluid->initial_rest_mass(), fluid->sigma());
   })
      .after_if_present("star.setup")
      .after_if_present("horizon.publish")
      .before_if_present("equation.shift.setup")
      .doc("with mass_ratio > 0: Mhat_BH and xhat_BH from the initial star, before the shift builds its cube");

  b.schedule(Bin::initial, "binary_initial", [hole](Context& ctx) {
     const double mu = ctx.params().real("mass_ratio");
     const auto* fluid = ctx.services().find<Fluid>("star");
     if (!(mu > 0) || !fluid) return;
     // The star's initial data may have changed sigma (the hole shrinks it, sigma_0 = R_iso/(Rhat
     // phi_ext^2)): the first field solve must see Mhat_BH = mu M_NS/sigma with that sigma.
     const HoleValues h = scaled_hole(ctx.services().get<Grid>("grid"), *fluid,
                                      ctx.services().get<TovFamily>("tov_family"), mu, fluid->initial_rest_mass());
     hole->mass = h.mass;
     hole->x = h.position;
     if (!h.moved.empty()) ctx.log().info("puncture: {}", h.moved);
     ctx.log().info("puncture of the binary: Mhat_BH = {:.9g}, xhat_BH = {:.9g} for the initial sigma = {:.9g}", hole->mass,
                    hole->x[0], fluid->sigma());
   })
      .after_if_present("star.initial_data")
      .doc("with mass_ratio > 0: the hole again from the initial star, whose initial data set sigma_0");

  // INITIAL places the hole for the initial star; a resume puts back where the loop had moved it.
  const auto restore_hole = [hole](Context&, const core::CheckpointReader& in) {
        const std::vector<double> h = in.reals("hole");
        if (h.size() != 7) throw core::InputError("puncture: the checkpoint's hole is malformed");
        hole->mass = h[0];
        hole->x = {h[1], h[2], h[3]};
        hole->p = {h[4], h[5], h[6]};
        hole->before_update.reset();
        if (in.has("before_update")) {
          const std::vector<double> b4 = in.reals("before_update");
          if (b4.size() != 7) throw core::InputError("puncture: the checkpoint's hole is malformed");
          hole->before_update = Hole::Saved{b4[0], {b4[1], b4[2], b4[3]}, {b4[4], b4[5], b4[6]}};
        }
      };
  b.checkpoint(
      [hole](Context&, core::CheckpointWriter& out) {
        out.put("hole", {hole->mass, hole->x[0], hole->x[1], hole->x[2], hole->p[0], hole->p[1], hole->p[2]});
        if (const auto& b4 = hole->before_update)
          out.put("before_update", {b4->mass, b4->x[0], b4->x[1], b4->x[2], b4->p[0], b4->p[1], b4->p[2]});
      },
      restore_hole);
  // A sequence neighbour's hole (mass, position, momentum) matches the fields and star it hands over.
  b.warm_start(restore_hole);

  b.schedule(Bin::update, "binary_update", [hole](Context& ctx) {
     const double mu = ctx.params().real("mass_ratio");
     const auto* fluid = ctx.services().find<Fluid>("star");
     const bool irreducible = ctx.params().string("mass_target") == "irreducible";
     const bool on_target = !irreducible || std::fabs(hole->irreducible_error) <= ctx.params().real("mass_tolerance");
     // At the converged step the star kept its sources: so does the hole (consistent output), once
     // its mass is on target.
     if (!(mu > 0) || !fluid || (fluid->settled() && on_target)) {
       hole->before_update.reset();  // this update changed nothing
       return;
     }
     auto& grid = ctx.services().get<Grid>("grid");
     const double m0 = fluid->rest_mass();
     HoleValues h = scaled_hole(grid, *fluid, ctx.services().get<TovFamily>("tov_family"), mu, m0);
     if (irreducible) {
       // h.mass is the target mu M_NS/sigma; the horizon of the last solve measured M_irr for the current bare mass.
       const double m_irr = ctx.services().get<ApparentHorizon>("horizon").irreducible_mass_hat();
       hole->irreducible_error = m_irr / h.mass - 1;
       h.mass = irreducible_bare_mass(hole->mass, m_irr, h.mass);
       ctx.show_progress("bh_irreducible_error", hole->irreducible_error);
     }
     h.momentum = {0.0, balancing_momentum(grid, *fluid), 0.0};
     if (!h.moved.empty()) ctx.log().info("puncture: {}", h.moved);
     ctx.show_progress("bh_position_x_hat", h.position[0]);
     ctx.show_progress("bh_momentum_y_hat", h.momentum[1]);
     ctx.log().detail("puncture: Mhat_BH = {:.12g}, xhat_BH = {:.12g}, Phat_y = {:.6e} (M0 = {:.12g})", h.mass, h.position[0],
                    h.momentum[1], m0);
     hole->before_update = Hole::Saved{hole->mass, hole->x, hole->p};
     hole->mass = h.mass;
     hole->x = h.position;
     hole->p = h.momentum;
   })
      .after_if_present("star.outer_step")
      .doc("with mass_ratio > 0, after the star's outer step: Mhat_BH = mu_bn M_NS(M0)/sigma, xhat_BH = -xhat_C/mu_bn, "
           "Phat_y = -sigma^2 Int phi^10 j^y (mass_target = irreducible: Mhat_BH scaled by mu_bn M_NS/M_irr); "
           "skipped at the converged step once the mass is on target");

  b.check("mass_on_target", [hole](Context& ctx) {
     if (ctx.params().string("mass_target") != "irreducible" || !(ctx.params().real("mass_ratio") > 0))
       return core::Convergence{true, "the bare mass is the target"};
     return core::Convergence{std::fabs(hole->irreducible_error) <= ctx.params().real("mass_tolerance"),
                              fmt::format("M_irr/(mu_bn M_NS) - 1 = {:.3e} (tol {:.1e})", hole->irreducible_error,
                                          ctx.params().real("mass_tolerance"))};
   }).doc("with mass_target = irreducible, |M_irr/(mu_bn M_NS) - 1| <= mass_tolerance at the last update");

  b.schedule(Bin::retreat, "undo_update", [hole](Context& ctx) {
     // Without a binary update since the last one undone there is nothing to put back.
     if (!hole->before_update) return;
     hole->mass = hole->before_update->mass;
     hole->x = hole->before_update->x;
     hole->p = hole->before_update->p;
     hole->before_update.reset();
     ctx.log().detail("puncture: back at Mhat_BH = {:.12g}, xhat_BH = {:.12g}, Phat_y = {:.6e}", hole->mass, hole->x[0],
                      hole->p[1]);
   }).doc("the hole's mass, position and momentum back to before its last binary update");

  b.schedule(Bin::analysis, "report", [hole](Context& ctx) {
     const auto* fluid = ctx.services().find<Fluid>("star");
     const double sigma = fluid ? fluid->sigma() : 1.0;
     ctx.set_scalar("bh_bare_mass", sigma * hole->mass);
     ctx.set_scalar("bh_position_x", sigma * hole->x[0]);
     ctx.set_scalar("bh_momentum_y", sigma * hole->p[1]);
     // The whole vectors too, for readers that add the puncture's 1/r exactly (docs/output-format.md).
     ctx.set_scalar("bh_position_y", sigma * hole->x[1]);
     ctx.set_scalar("bh_position_z", sigma * hole->x[2]);
     ctx.set_scalar("bh_momentum_x", sigma * hole->p[0]);
     ctx.set_scalar("bh_momentum_z", sigma * hole->p[2]);
     ctx.set_scalar("bh_bare_mass_hat", hole->mass);
     ctx.set_scalar("bh_position_x_hat", hole->x[0]);
     ctx.set_scalar("bh_momentum_y_hat", hole->p[1]);
   }).doc("bh_bare_mass, bh_position_x/y/z, bh_momentum_x/y/z (physical: sigma times the hatted values) and the "
          "hatted bh_bare_mass_hat, bh_position_x_hat, bh_momentum_y_hat");
}

}  // namespace
}  // namespace bhnsid::puncture

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "puncture", "0.1",
                                     "black hole: Brandt-Brugmann puncture with Bowen-York momentum (service puncture)",
                                     &bhnsid::puncture::declare};
  return &info;
}
