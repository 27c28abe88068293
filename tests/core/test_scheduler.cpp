// Schedule ordering: bins, before/after, tie-breaking, cycles and dangling references.
#include <catch2/catch.hpp>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/scheduler.hpp"

using namespace bhnsid::core;
using Catch::Matchers::Contains;

namespace {
PluginDecl plugin(const std::string& name) {
  PluginDecl d;
  d.name = name;
  return d;
}
std::vector<std::string> names(const Schedule& s, Bin bin) {
  std::vector<std::string> out;
  for (const auto* e : s.at(bin)) out.push_back(e->full_name());
  return out;
}
const ScheduledFn nothing = [](Context&) {};
}  // namespace

TEST_CASE("core.schedule.default_order_is_plugin_list_then_declaration", "[core][schedule]") {
  // Without constraints, entries run in the order of the plugins list, then of declaration.
  PluginDecl a = plugin("a"), b = plugin("b");
  PluginBuilder(b).schedule(Bin::setup, "one", nothing);
  PluginBuilder(a).schedule(Bin::setup, "one", nothing);
  PluginBuilder(a).schedule(Bin::setup, "two", nothing);
  CHECK(names(build_schedule({&b, &a}), Bin::setup) == std::vector<std::string>{"b.one", "a.one", "a.two"});
}

TEST_CASE("core.schedule.before_and_after", "[core][schedule]") {
  // before/after override the default order, across plugins; references to inactive plugins are dropped.
  PluginDecl a = plugin("a"), b = plugin("b");
  PluginBuilder(a).schedule(Bin::initial, "x", nothing).after("b.z");
  PluginBuilder(a).schedule(Bin::initial, "y", nothing).before("a.x").after("missing_plugin.q");
  PluginBuilder(b).schedule(Bin::initial, "z", nothing);
  CHECK(names(build_schedule({&a, &b}), Bin::initial) == std::vector<std::string>{"a.y", "b.z", "a.x"});
}

TEST_CASE("core.schedule.after_a_capability", "[core][schedule]") {
  // "capability.entry" orders against the entry of whichever active plugin implements the capability
  // (a plugin orders itself against a role without naming the plugin); dropped when none does.
  PluginDecl a = plugin("a"), b = plugin("b");
  PluginBuilder(a).schedule(Bin::update, "follow", nothing).after("role.step");
  PluginBuilder(b).implements("role");
  PluginBuilder(b).schedule(Bin::update, "step", nothing);
  CHECK(names(build_schedule({&a, &b}), Bin::update) == std::vector<std::string>{"b.step", "a.follow"});
  PluginDecl c = plugin("c");
  PluginBuilder(c).schedule(Bin::update, "follow", nothing).after("role.step");
  CHECK(names(build_schedule({&c}), Bin::update) == std::vector<std::string>{"c.follow"});
}

TEST_CASE("core.schedule.cycle_and_bad_references", "[core][schedule]") {
  // A cycle, a reference to a missing entry of an active plugin, or across bins is an error.
  PluginDecl a = plugin("a");
  PluginBuilder(a).schedule(Bin::setup, "p", nothing).before("a.q");
  PluginBuilder(a).schedule(Bin::setup, "q", nothing).before("a.p");
  CHECK_THROWS_WITH(build_schedule({&a}), Contains("cycle") && Contains("a.p") && Contains("a.q"));

  PluginDecl c = plugin("c");
  PluginBuilder(c).schedule(Bin::setup, "p", nothing).after("c.nope");
  CHECK_THROWS_WITH(build_schedule({&c}), Contains("has no such entry"));

  PluginDecl d = plugin("d");
  PluginBuilder(d).schedule(Bin::setup, "p", nothing).after("d.q");
  PluginBuilder(d).schedule(Bin::initial, "q", nothing);
  CHECK_THROWS_WITH(build_schedule({&d}), Contains("another bin"));
}

TEST_CASE("core.schedule.loop_bins_are_printed_as_a_loop", "[core][schedule]") {
  // The printed schedule shows the loop and its bins.
  PluginDecl a = plugin("a");
  PluginBuilder(a).schedule(Bin::solve, "s", nothing).doc("solve it");
  PluginBuilder(a).check("c", [](Context&) { return Convergence{true, ""}; });
  const std::string text = format_schedule(build_schedule({&a}));
  CHECK_THAT(text, Contains("loop (until every CHECK") && Contains("SOLVE") && Contains("a.s") &&
                       Contains("solve it") && Contains("CHECK"));
}
