// The YAML reader: positions, duplicate keys, hostile nesting and sizes.
#include <catch2/catch.hpp>

#include <string>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/yaml_tree.hpp"

using namespace bhnsid::core;
using Catch::Matchers::Contains;

TEST_CASE("core.yaml.keeps_positions", "[core][yaml]") {
  // Every node knows its line and column so that errors can point at the text.
  const YamlNode root = parse_yaml("plugins: [a, b]\ngrid:\n  spacing: 0.03\n", "f.yaml");
  REQUIRE(root.kind == YamlNode::Kind::map);
  REQUIRE(root.entries.size() == 2);
  CHECK(root.entries[1].first.scalar == "grid");
  const auto& spacing = root.entries[1].second.entries[0];
  CHECK(spacing.first.pos.line == 3);
  CHECK(spacing.first.pos.column == 3);
  CHECK(spacing.second.scalar == "0.03");
  CHECK(root.entries[0].second.items[1].scalar == "b");
}

TEST_CASE("core.yaml.nested_sequences_of_maps", "[core][yaml]") {
  // Keys and values of maps inside lists are paired correctly.
  const YamlNode root = parse_yaml("a:\n  - {x: 1, y: 2}\n  - {x: 3}\nb: 4\n", "f.yaml");
  REQUIRE(root.entries.size() == 2);
  const auto& list = root.entries[0].second;
  REQUIRE(list.items.size() == 2);
  CHECK(list.items[0].entries[1].first.scalar == "y");
  CHECK(list.items[0].entries[1].second.scalar == "2");
  CHECK(root.entries[1].second.scalar == "4");
}

TEST_CASE("core.yaml.duplicate_key_is_an_error", "[core][yaml]") {
  // yaml-cpp keeps the last of two equal keys silently; we refuse and name both lines.
  CHECK_THROWS_WITH(parse_yaml("grid:\n  n: 1\n  n: 2\n", "f.yaml"),
                    Contains("f.yaml:3:3") && Contains("duplicate key 'n'") && Contains("line 2"));
}

TEST_CASE("core.yaml.deep_nesting_is_refused_without_overflow", "[core][yaml]") {
  // 10,000 nested lists must give a clear error, not a stack overflow.
  const std::string deep = "plugins: " + std::string(10000, '[') + std::string(10000, ']');
  CHECK_THROWS_WITH(parse_yaml(deep, "deep.yaml"), Contains("nesting deeper than"));
  const std::string deep_maps = [] {
    std::string s;
    for (int i = 0; i < 10000; ++i) s += "{a: ";
    return s + "1" + std::string(10000, '}');
  }();
  CHECK_THROWS_AS(parse_yaml(deep_maps, "deep.yaml"), InputError);
}

TEST_CASE("core.yaml.huge_input_is_refused", "[core][yaml]") {
  // Input beyond the size limit is refused before parsing.
  const std::string huge(yaml_max_bytes + 1, 'a');
  CHECK_THROWS_WITH(parse_yaml(huge, "huge.yaml"), Contains("too large"));
}

TEST_CASE("core.yaml.syntax_errors_anchors_and_documents", "[core][yaml]") {
  // Syntax errors carry line and column; features a parameter file never needs are refused.
  CHECK_THROWS_WITH(parse_yaml("a: [1, 2\nb: 3\n", "f.yaml"), Contains("f.yaml:") && Contains("YAML syntax error"));
  CHECK_THROWS_WITH(parse_yaml("a: &x 1\nb: *x\n", "f.yaml"), Contains("anchors"));
  CHECK_THROWS_WITH(parse_yaml("a: 1\n---\nb: 2\n", "f.yaml"), Contains("more than one YAML document"));
  CHECK_THROWS_WITH(parse_yaml("? [1, 2]\n: 3\n", "f.yaml"), Contains("a key must be a plain name"));
}

TEST_CASE("core.yaml.quoted_scalars_are_marked", "[core][yaml]") {
  // A quoted "1.0" must not be mistaken for a number later.
  const YamlNode root = parse_yaml("a: \"1.0\"\nb: 1.0\n", "f.yaml");
  CHECK_FALSE(root.entries[0].second.plain);
  CHECK(root.entries[1].second.plain);
}
