#include <catch2/catch.hpp>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/yaml_tree.hpp"

using namespace bhnsid::core;

TEST_CASE("core.yaml.keeps_positions", "[core][yaml]") {
  // Requirement: every node knows its line and column so errors can point at the text.
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
