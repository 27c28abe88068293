// Parameter files against declarations: types, ranges, keywords, defaults, overrides.
#include <catch2/catch.hpp>

#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/parfile.hpp"

using namespace bhnsid::core;
using Catch::Matchers::Contains;

namespace {
PluginDecl example_decl() {
  PluginDecl d;
  d.name = "grid";
  PluginBuilder b(d);
  b.integer("intervals").doc("intervals per side").default_value(std::int64_t{128}).at_least(4);
  b.real("spacing").doc("dx").required(0.03).greater_than(0);
  b.boolean("verbose").doc("chatty").default_value(false);
  b.keyword("symmetry", {"none", "equatorial"}).doc("reflection").default_value(std::string("none"));
  b.real_vector("centre").doc("centre").default_value(std::vector<double>{0, 0, 0}).length(3);
  b.string("label").doc("free text").default_value(std::string("x"));
  return d;
}

std::map<std::string, ParamSection> resolve_text(const std::string& text, const std::vector<std::string>& sets = {}) {
  static const PluginDecl decl = example_decl();
  ParFile file = parse_parfile(parse_yaml(text, "p.yaml"));
  for (const auto& s : sets) apply_override(file, s);
  return resolve_params(file, {&core_declaration(), &decl}, {"tov"});
}
}  // namespace

TEST_CASE("core.params.values_and_defaults", "[core][params]") {
  // Given values are typed; missing ones take their defaults.
  const auto p = resolve_text("plugins: [grid]\ngrid: {spacing: 0.015, symmetry: equatorial, centre: [1, 2.5, -3]}\n");
  const auto& g = p.at("grid");
  CHECK(g.real("spacing") == 0.015);
  CHECK(g.integer("intervals") == 128);
  CHECK(g.string("symmetry") == "equatorial");
  CHECK(g.real_vector("centre") == std::vector<double>{1, 2.5, -3});
  CHECK(g.boolean("verbose") == false);
  CHECK(p.at("run").integer("max_iterations") == 100);
}

TEST_CASE("core.params.overrides", "[core][params]") {
  // --set replaces a file value or adds a missing one, with the value read as YAML.
  const auto p = resolve_text("plugins: [grid]\ngrid: {spacing: 0.015}\n",
                              {"grid.spacing=0.03", "grid.centre=[0, 0.3, 0]", "run.max_iterations=7"});
  CHECK(p.at("grid").real("spacing") == 0.03);
  CHECK(p.at("grid").real_vector("centre")[1] == 0.3);
  CHECK(p.at("run").integer("max_iterations") == 7);
  CHECK_THROWS_WITH(resolve_text("plugins: [grid]\ngrid: {spacing: 1}\n", {"grid.spacing"}),
                    Contains("expected section.key=value"));
  CHECK_THROWS_WITH(resolve_text("plugins: [grid]\ngrid: {spacing: 1}\n", {"grid.spacing=[1,"}),
                    Contains("--set grid.spacing=[1,") && Contains("YAML syntax error"));
  CHECK_THROWS_WITH(resolve_text("plugins: [grid]\ngrid: {spacing: 1}\n", {"grid.spaceing=1"}),
                    Contains("did you mean 'spacing'"));
}

TEST_CASE("core.params.bad_values", "[core][params]") {
  // Each wrong value is one clear error with position, key, expectation and what was given.
  const auto bad = [](const std::string& section_body) {
    return "plugins: [grid]\ngrid: {spacing: 0.1, " + section_body + "}\n";
  };
  CHECK_THROWS_WITH(resolve_text(bad("intervals: 2")), Contains("p.yaml:2:") && Contains("grid.intervals") &&
                                                           Contains("[4, inf)") && Contains("'2'"));
  CHECK_THROWS_WITH(resolve_text(bad("intervals: 12.5")), Contains("expected an integer"));
  CHECK_THROWS_WITH(resolve_text(bad("intervals: 99999999999999999999")), Contains("fits in 64 bits"));
  CHECK_THROWS_WITH(resolve_text(bad("verbose: yes")), Contains("true or false"));
  CHECK_THROWS_WITH(resolve_text(bad("symmetry: equitorial")), Contains("did you mean 'equatorial'"));
  CHECK_THROWS_WITH(resolve_text(bad("centre: [1, 2]")), Contains("exactly 3 reals"));
  CHECK_THROWS_WITH(resolve_text(bad("centre: 1")), Contains("a list of reals"));
  CHECK_THROWS_WITH(resolve_text(bad("intervals: \"64\"")), Contains("expected an integer"));
  CHECK_THROWS_WITH(resolve_text(bad("label: [a]")), Contains("expected a string"));
  for (const char* non_finite : {".nan", ".NaN", "nan", ".inf", "-.inf", "inf", "1e999"})
    CHECK_THROWS_WITH(resolve_text("plugins: [grid]\ngrid: {spacing: " + std::string(non_finite) + "}\n"),
                      Contains("finite real"));
  CHECK_THROWS_WITH(resolve_text("plugins: [grid]\ngrid: {spacing: -1}\n"), Contains("(0, inf)"));
}

TEST_CASE("core.params.unknown_missing_and_inactive", "[core][params]") {
  // Unknown keys and sections, required parameters, and sections of inactive plugins are errors.
  CHECK_THROWS_WITH(resolve_text("plugins: [grid]\ngrid: {spacing: 1, spcing: 2}\n"),
                    Contains("unknown parameter 'grid.spcing'") && Contains("did you mean 'spacing'"));
  CHECK_THROWS_WITH(resolve_text("plugins: [grid]\ngird: {spacing: 1}\n"),
                    Contains("unknown section 'gird'") && Contains("did you mean 'grid'"));
  CHECK_THROWS_WITH(resolve_text("plugins: [grid]\n"), Contains("grid.spacing is required") && Contains("e.g. 0.03"));
  CHECK_THROWS_WITH(resolve_text("plugins: [grid]\ngrid: {spacing: 1}\ntov: {central_density: 0.1}\n"),
                    Contains("plugin 'tov', which is not in the plugins: list"));
  CHECK_THROWS_WITH(resolve_text("plugins: [grid]\ngrid: 3\n"), Contains("expected a mapping of parameters"));
}

TEST_CASE("core.params.plugins_list_shape", "[core][params]") {
  // The plugins list must exist, be a non-empty list of names and name each plugin once.
  CHECK_THROWS_WITH(parse_parfile(parse_yaml("grid: {}\n", "p.yaml")), Contains("no 'plugins:' list"));
  CHECK_THROWS_WITH(parse_parfile(parse_yaml("plugins: []\n", "p.yaml")), Contains("non-empty list"));
  CHECK_THROWS_WITH(parse_parfile(parse_yaml("plugins: grid\n", "p.yaml")), Contains("non-empty list"));
  CHECK_THROWS_WITH(parse_parfile(parse_yaml("plugins: [grid, grid]\n", "p.yaml")), Contains("listed twice"));
  CHECK_THROWS_WITH(parse_parfile(parse_yaml("plugins: [Grid]\n", "p.yaml")), Contains("expected a plugin name"));
  CHECK_THROWS_WITH(parse_parfile(parse_yaml("- a\n- b\n", "p.yaml")), Contains("expected a mapping"));
}

TEST_CASE("core.params.format_value_round_trips", "[core][params]") {
  // Values written into params.yaml read back to the same bits.
  ParamSpec real_spec;
  real_spec.name = "x";
  real_spec.type = ParamType::real;
  for (double x : {0.1, 1.0 / 3.0, 1e-300, 6.02214076e23, -0.0, 3.0, -2.5e-7}) {
    const YamlNode node = parse_yaml(format_value(ParamValue{x}), "v");
    const double back = std::get<double>(convert_value(real_spec, node, "x"));
    CHECK(back == x);
    CHECK(std::signbit(back) == std::signbit(x));
  }
  const ParamValue text = std::string("a: b # not a comment");
  CHECK(parse_yaml(format_value(text), "v").scalar == "a: b # not a comment");
}

TEST_CASE("core.params.declaration_checks", "[core][params]") {
  // A plugin's own declaration errors (no doc, default out of range, duplicates) are caught at load.
  PluginDecl d;
  d.name = "broken";
  PluginBuilder b(d);
  b.real("x").default_value(1.0);
  CHECK_THROWS_WITH(validate_declaration(d), Contains("without a doc"));
  d.params.clear();
  b.real("x").doc("x").default_value(-1.0).at_least(0);
  CHECK_THROWS_WITH(validate_declaration(d), Contains("default for 'x'"));
  d.params.clear();
  b.real("x").doc("x").default_value(1.0);
  b.real("x").doc("x").default_value(1.0);
  CHECK_THROWS_WITH(validate_declaration(d), Contains("parameter 'x' twice"));
}
