#pragma once
// A YAML document as a plain tree that keeps every key (yaml-cpp's node API silently drops
// duplicates) and the line and column of every node, so errors can point at the text.
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace bhnsid::core {

struct TextPos {
  std::string source;  ///< file name, or "--set ..." for command-line overrides
  int line = 0;        ///< 1-based; 0 when unknown
  int column = 0;      ///< 1-based
  std::string str() const;  ///< "file:line:col"
};

struct YamlEntry;

struct YamlNode {
  enum class Kind { null, scalar, sequence, map };
  Kind kind = Kind::null;
  std::string scalar;
  bool plain = true;  ///< false for quoted scalars: never read as a number or a bool
  std::vector<YamlNode> items;                       ///< sequence
  /// Map, in file order, keys are scalars. A vector of a struct declared below rather than of
  /// std::pair<YamlNode, YamlNode>: the standard lets vector (not pair) take a type that is still
  /// incomplete, and clang holds us to it.
  std::vector<YamlEntry> entries;
  TextPos pos;

  const char* kind_name() const;
};

struct YamlEntry {
  YamlNode first;   ///< the key, a scalar
  YamlNode second;  ///< the value
};

/// Limits that keep hostile input from exhausting the stack or memory.
inline constexpr int yaml_max_depth = 32;
/// 1 MiB: a parameter file is a few kilobytes, and yaml-cpp's parser alone takes about a second
/// for 4 MiB of short keys (docs/reliability.md), so the largest accepted file checks in a fraction.
inline constexpr std::size_t yaml_max_bytes = 1u << 20;
/// Longest map key: parameter and section names are short words, and every message quotes the key.
inline constexpr std::size_t yaml_max_key_length = 128;

/// Parses one document; throws InputError "source:line:col: what" on syntax errors, duplicate keys,
/// non-scalar or overlong keys, anchors/aliases, tags, more than one document, or nesting deeper
/// than yaml_max_depth.
YamlNode parse_yaml(const std::string& text, const std::string& source);
/// Reads a parameter file's bytes; missing, unreadable, non-regular (a FIFO, a device: reading one
/// could block forever), empty or oversized files are InputErrors.
std::string read_parfile_text(const std::filesystem::path& path);
/// Reads and parses a file (read_parfile_text, then parse_yaml).
YamlNode read_yaml_file(const std::filesystem::path& path);

}  // namespace bhnsid::core
