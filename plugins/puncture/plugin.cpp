// The puncture plugin (implements "puncture"): the black hole as a Brandt-Brugmann puncture of bare
// mass Mhat_BH at xhat_BH with a Bowen-York momentum Phat_BH (physics-notes §1.3, §2.6). It publishes
// the Puncture service that the field equations read: the analytic Mhat/(2 rhat) part of phi
// (hamiltonian), the Bowen-York part of Ahat^ij (momentum), the excision cube (shift). Here the three
// are parameters; the binary updates them from the star.
#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
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
};

std::array<double, 3> vec3(const std::vector<double>& v) { return {v.at(0), v.at(1), v.at(2)}; }

void declare(core::PluginBuilder& b) {
  auto hole = std::make_shared<Hole>();
  b.implements("puncture");
  b.require("grid");  // the position is checked against grid.n and grid.dx

  b.real("bare_mass").doc("bare mass Mhat_BH of the puncture (hatted units)").required(1.0).greater_than(0);
  b.real_vector("position")
      .doc("hatted position xhat_BH; must not be a grid point of any multigrid level (1/r there)")
      .required(std::vector<double>{0.0075, 0, 0})
      .length(3);
  b.real_vector("momentum")
      .doc("Bowen-York momentum Phat_BH (hatted units); the z component must be 0 with equatorial symmetry")
      .default_value(std::vector<double>{0, 0, 0})
      .length(3);

  b.schedule(Bin::paramcheck, "check", [](Context& ctx) {
     const auto& p = ctx.params();
     const std::array<double, 3> x = vec3(p.real_vector("position")), mom = vec3(p.real_vector("momentum"));
     if (!(p.real("bare_mass") > 0 && std::isfinite(p.real("bare_mass"))))
       throw core::InputError(fmt::format("puncture.bare_mass = {}: expected a finite value > 0", p.real("bare_mass")));
     check_off_the_points(ctx, x);
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
}

}  // namespace
}  // namespace bhnsid::puncture

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "puncture", "0.1",
                                     "black hole: Brandt-Brugmann puncture with Bowen-York momentum (service puncture)",
                                     &bhnsid::puncture::declare};
  return &info;
}
