#include "bhnsid/core/parfile.hpp"

#include <fstream>
#include <iterator>
#include <fmt/format.h>

#include <algorithm>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/nearest.hpp"

namespace bhnsid::core {

namespace {
bool is_name(const std::string& s) {
  if (s.empty() || !(std::islower(static_cast<unsigned char>(s[0])))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_';
  });
}
}  // namespace

ParFile parse_parfile(const YamlNode& root) {
  ParFile file;
  file.source = root.pos.source;
  if (root.kind != YamlNode::Kind::map)
    throw InputError(fmt::format("{}: expected a mapping with a 'plugins:' list at the top level, got {}",
                                 root.pos.str(), root.kind_name()));
  bool have_plugins = false;
  for (const auto& [key, value] : root.entries) {
    if (key.scalar == "plugins") {
      have_plugins = true;
      if (value.kind != YamlNode::Kind::sequence || value.items.empty())
        throw InputError(fmt::format("{}: plugins: expected a non-empty list of plugin names, e.g. [grid, multigrid]",
                                     value.pos.str()));
      for (const auto& item : value.items) {
        if (item.kind != YamlNode::Kind::scalar || !is_name(item.scalar))
          throw InputError(fmt::format("{}: plugins: expected a plugin name (lower case, digits, '_'), got {}",
                                       item.pos.str(), item.kind == YamlNode::Kind::scalar ? "'" + item.scalar + "'" : item.kind_name()));
        if (std::find(file.plugins.begin(), file.plugins.end(), item.scalar) != file.plugins.end())
          throw InputError(fmt::format("{}: plugins: '{}' is listed twice", item.pos.str(), item.scalar));
        file.plugins.push_back(item.scalar);
        file.plugin_pos.push_back(item.pos);
      }
      continue;
    }
    if (value.kind != YamlNode::Kind::map && value.kind != YamlNode::Kind::null)
      throw InputError(fmt::format("{}: section '{}': expected a mapping of parameters, got {}", value.pos.str(),
                                   key.scalar, value.kind_name()));
    file.sections.push_back(ParSection{key.scalar, key.pos, value.entries});
  }
  if (!have_plugins)
    throw InputError(fmt::format("{}: no 'plugins:' list; expected e.g. 'plugins: [grid, multigrid]'", file.source));
  return file;
}

ParFile load_parfile(const std::filesystem::path& path) {
  ParFile file = parse_parfile(read_yaml_file(path));
  // read_yaml_file has checked that the file exists, is readable and not too large.
  std::ifstream in(path, std::ios::binary);
  file.text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return file;
}

void apply_override(ParFile& file, const std::string& assignment) {
  const std::string where = "--set " + assignment;
  const auto eq = assignment.find('=');
  const auto dot = assignment.find('.');
  if (eq == std::string::npos || dot == std::string::npos || dot > eq || dot == 0 || dot + 1 == eq)
    throw InputError(fmt::format("{}: expected section.key=value, e.g. --set grid.dx=0.03", where));
  const std::string section = assignment.substr(0, dot);
  const std::string key = assignment.substr(dot + 1, eq - dot - 1);
  if (section == "plugins" || !is_name(section) || !is_name(key))
    throw InputError(fmt::format("{}: expected section.key=value with names in lower case, digits and '_'", where));
  YamlNode value = parse_yaml(assignment.substr(eq + 1), where);
  if (value.kind == YamlNode::Kind::map)
    throw InputError(fmt::format("{}: the value must be a scalar or a list", where));
  YamlNode key_node;
  key_node.kind = YamlNode::Kind::scalar;
  key_node.scalar = key;
  key_node.pos = TextPos{where, 0, 0};
  value.pos = key_node.pos;
  auto it = std::find_if(file.sections.begin(), file.sections.end(), [&](const ParSection& s) { return s.name == section; });
  if (it == file.sections.end()) {
    file.sections.push_back(ParSection{section, key_node.pos, {}});
    it = std::prev(file.sections.end());
  }
  for (auto& [k, v] : it->entries)
    if (k.scalar == key) {
      v = std::move(value);
      return;
    }
  it->entries.push_back(YamlEntry{std::move(key_node), std::move(value)});
}

const PluginDecl& core_declaration() {
  static const PluginDecl decl = [] {
    PluginDecl d;
    d.name = "run";
    d.version = "core";
    d.description = "the core: outer-loop limits and threads";
    PluginBuilder b(d);
    b.integer("max_iterations")
        .doc("most iterations of the SOLVE/UPDATE/CHECK loop before the run is declared failed")
        .default_value(std::int64_t{100})
        .at_least(1);
    b.integer("max_retreats")
        .doc("times one loop iteration may undo the last UPDATE and redo it with half the step after a SOLVE entry "
             "fails with a step failure (a diverging solve), before the run is declared failed; 0: never")
        .default_value(std::int64_t{4})
        .at_least(0)
        .at_most(30);
    b.integer("checkpoint_every")
        .doc("save the run's state to RUN_DIR/checkpoints at most every this many loop iterations (see "
             "checkpoint_overhead; always at convergence), the newest two kept, for bhnsid run --resume; 0: never")
        .default_value(std::int64_t{1})
        .at_least(0);
    b.real("checkpoint_overhead")
        .doc("a checkpoint is skipped while the last one took more than this fraction of the time since it ended, so "
             "that checkpoints cost at most about this fraction of the run (the converged iteration's is always "
             "written)")
        .default_value(0.1)
        .greater_than(0);
    b.integer("threads")
        .doc("OpenMP threads for every kernel; 0 keeps OMP_NUM_THREADS or the machine's default")
        .default_value(std::int64_t{0})
        .at_least(0);
    return d;
  }();
  return decl;
}

}  // namespace bhnsid::core
