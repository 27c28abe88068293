// Schedule ordering: bins, before/after, tie-breaking, cycles and dangling references.
#include <catch2/catch.hpp>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
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
  // before/after name "capability.entry" and override the default order, across plugins; an optional
  // reference to a capability that no active plugin implements is dropped.
  PluginDecl a = plugin("a"), b = plugin("b");
  PluginBuilder(a).implements("first");
  PluginBuilder(b).implements("second");
  PluginBuilder(a).schedule(Bin::initial, "x", nothing).after("second.z");
  PluginBuilder(a).schedule(Bin::initial, "y", nothing).before("first.x").after_if_present("absent.q");
  PluginBuilder(b).schedule(Bin::initial, "z", nothing);
  CHECK(names(build_schedule({&a, &b}), Bin::initial) == std::vector<std::string>{"a.y", "b.z", "a.x"});
}

TEST_CASE("core.schedule.a_reference_means_whichever_plugin_implements_the_capability", "[core][schedule]") {
  // "lapse.setup" is the setup of whichever active plugin implements `lapse`: two plugins filling the
  // role are swapped without touching the plugin that orders itself against it.
  for (const char* name : {"lapse_one", "lapse_two"}) {
    PluginDecl user = plugin("user"), lapse = plugin(name);
    PluginBuilder(user).schedule(Bin::setup, "read", nothing).after("lapse.setup");
    PluginBuilder(lapse).implements("lapse");
    PluginBuilder(lapse).schedule(Bin::setup, "setup", nothing);
    CHECK(names(build_schedule({&user, &lapse}), Bin::setup) == std::vector<std::string>{std::string(name) + ".setup", "user.read"});
  }
}

TEST_CASE("core.schedule.dotted_capabilities_split_at_the_last_dot", "[core][schedule]") {
  // Capabilities may hold dots ("equation.hamiltonian"); entry names may not, so the reference splits
  // at its last dot.
  PluginDecl user = plugin("user"), ham = plugin("ham");
  PluginBuilder(user).schedule(Bin::setup, "read", nothing).after("equation.hamiltonian.setup");
  PluginBuilder(ham).implements("equation.hamiltonian");
  PluginBuilder(ham).schedule(Bin::setup, "setup", nothing);
  CHECK(names(build_schedule({&user, &ham}), Bin::setup) == std::vector<std::string>{"ham.setup", "user.read"});
}

TEST_CASE("core.schedule.unresolved_references_are_errors_naming_them", "[core][schedule]") {
  // A required reference that no active plugin implements, one that names a plugin instead of a
  // capability, an absent entry of the implementing plugin: each an error naming entry and reference.
  PluginDecl c = plugin("c");
  PluginBuilder(c).schedule(Bin::setup, "p", nothing).after("lapse.setup");
  CHECK_THROWS_WITH(build_schedule({&c}), Contains("c.p") && Contains("'lapse.setup'") &&
                                              Contains("no active plugin implements 'lapse'"));

  PluginDecl user = plugin("user"), named = plugin("hamiltonian");
  PluginBuilder(user).schedule(Bin::setup, "p", nothing).after("hamiltonian.setup");
  PluginBuilder(named).implements("equation.hamiltonian");
  PluginBuilder(named).schedule(Bin::setup, "setup", nothing);
  CHECK_THROWS_WITH(build_schedule({&user, &named}),
                    Contains("'hamiltonian.setup'") && Contains("references name a capability") &&
                        Contains("'equation.hamiltonian'"));

  PluginDecl d = plugin("d");
  PluginBuilder(d).implements("role");
  PluginBuilder(d).schedule(Bin::setup, "p", nothing).after("role.nope");
  CHECK_THROWS_WITH(build_schedule({&d}), Contains("d, which implements 'role', has no entry 'nope'"));

  PluginDecl e = plugin("e");
  PluginBuilder(e).schedule(Bin::setup, "p", nothing).after("nodot");
  CHECK_THROWS_WITH(build_schedule({&e}), Contains("'capability.entry'"));
}

TEST_CASE("core.schedule.cycle_and_other_bins", "[core][schedule]") {
  // A cycle, or an ordering across bins, is an error.
  PluginDecl a = plugin("a");
  PluginBuilder(a).implements("role");
  PluginBuilder(a).schedule(Bin::setup, "p", nothing).before("role.q");
  PluginBuilder(a).schedule(Bin::setup, "q", nothing).before("role.p");
  CHECK_THROWS_WITH(build_schedule({&a}), Contains("cycle") && Contains("a.p") && Contains("a.q"));

  PluginDecl d = plugin("d");
  PluginBuilder(d).implements("role");
  PluginBuilder(d).schedule(Bin::setup, "p", nothing).after("role.q");
  PluginBuilder(d).schedule(Bin::initial, "q", nothing);
  CHECK_THROWS_WITH(build_schedule({&d}), Contains("another bin"));
}

TEST_CASE("core.schedule.declarations_name_references_as_capability_entry", "[core][schedule]") {
  // A reference that cannot be "capability.entry" is a malformed declaration, caught at load.
  PluginDecl a = plugin("a");
  PluginBuilder(a).schedule(Bin::setup, "p", nothing).after("lapse");
  CHECK_THROWS_WITH(validate_declaration(a), Contains("plugin 'a'") && Contains("'lapse'") && Contains("capability.entry"));
  PluginDecl b = plugin("b");
  PluginBuilder(b).schedule(Bin::setup, "p", nothing).after("equation.lapse.setup");
  CHECK_NOTHROW(validate_declaration(b));
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
