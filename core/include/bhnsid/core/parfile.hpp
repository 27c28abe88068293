#pragma once
// Parameter files: the `plugins:` list and one section per active plugin (plus the core's `run`).
// Reading checks the shape; resolving checks every key and value against the declarations.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "bhnsid/core/params.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/core/yaml_tree.hpp"

namespace bhnsid::core {

struct ParSection {
  std::string name;
  TextPos pos;
  std::vector<YamlEntry> entries;  ///< key, value
};

struct ParFile {
  std::string source;
  std::string text;  ///< the file as read (load_parfile), for the run's records; empty for a parsed tree
  std::vector<std::string> plugins;
  std::vector<TextPos> plugin_pos;
  std::vector<ParSection> sections;  ///< in file order, `plugins` excluded
};

/// Shape checks only: a mapping at the top, a non-empty `plugins:` list of names without repeats,
/// every other top-level value a mapping (or empty).
ParFile parse_parfile(const YamlNode& root);
ParFile load_parfile(const std::filesystem::path& path);

/// Applies one "--set section.key=value" (value in YAML flow syntax, e.g. [0, 0.3, 0]).
void apply_override(ParFile& file, const std::string& assignment);

/// Converts a YAML value for the parameter `where` ("grid.spacing"); InputError when it does not fit.
ParamValue convert_value(const ParamSpec& spec, const YamlNode& node, const std::string& where);

/// Every section of the file checked against the active declarations (the core's `run` included),
/// defaults filled in. `known_inactive` are plugins on the path that the file does not activate:
/// a section for one of them is an error of its own kind.
std::map<std::string, ParamSection> resolve_params(const ParFile& file,
                                                   const std::vector<const PluginDecl*>& active,
                                                   const std::vector<std::string>& known_inactive);

/// The core's own section `run`, declared like a plugin's.
const PluginDecl& core_declaration();

}  // namespace bhnsid::core
