// TEST ONLY plugin for the shift's tests: a "puncture" service from parameters, with any bare mass
// (so that the shift's own refusal of Mhat <= 0 can be seen), an optional move of the hole after the
// first iteration (UPDATE) and a CHECK that asks for `iterations` outer iterations, so that a run
// solves once at `position` and once at `position + move`.
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace {

using bhnsid::core::Bin;
using bhnsid::core::Context;

class Hole final : public bhnsid::Puncture {
 public:
  double bare_mass() const override { return mass; }
  std::array<double, 3> position() const override { return x; }
  std::array<double, 3> momentum() const override { return p; }
  double mass = 0;
  std::array<double, 3> x{}, p{};
};

std::array<double, 3> vec3(const std::vector<double>& v) { return {v.at(0), v.at(1), v.at(2)}; }

void declare(bhnsid::core::PluginBuilder& b) {
  auto hole = std::make_shared<Hole>();
  b.implements("puncture");
  b.real("bare_mass").doc("Mhat_BH (any value, unchecked)").default_value(0.2);
  b.real_vector("position").doc("xhat_BH").default_value(std::vector<double>{0.013, 0.027, 0}).length(3);
  b.real_vector("momentum").doc("Phat_BH").default_value(std::vector<double>{0, -0.03, 0}).length(3);
  b.real_vector("move").doc("added to the position after the first iteration").default_value(std::vector<double>{0, 0, 0}).length(3);
  b.integer("iterations").doc("outer iterations before CHECK reports converged").default_value(std::int64_t{1}).at_least(1);

  b.schedule(Bin::startup, "publish", [hole](Context& ctx) {
     hole->mass = ctx.params().real("bare_mass");
     hole->x = vec3(ctx.params().real_vector("position"));
     hole->p = vec3(ctx.params().real_vector("momentum"));
     ctx.publish<bhnsid::Puncture>("puncture", hole);
   }).doc("publish the Puncture service");

  b.schedule(Bin::update, "move", [hole](Context& ctx) {
     if (ctx.iteration() != 1) return;
     const auto d = vec3(ctx.params().real_vector("move"));
     for (int a = 0; a < 3; ++a) hole->x[static_cast<std::size_t>(a)] += d[static_cast<std::size_t>(a)];
   }).doc("move the hole by `move` after the first iteration");

  b.check("iterations", [](Context& ctx) {
     const bool done = ctx.iteration() >= ctx.params().integer("iterations");
     return bhnsid::core::Convergence{done, done ? "done" : "more iterations asked"};
   }).doc("converged after `iterations` iterations");
}

}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "shift_test_puncture", "1.0",
                                     "test: a movable puncture service for the shift's tests", &declare};
  return &info;
}
