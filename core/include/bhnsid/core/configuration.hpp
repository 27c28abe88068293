#pragma once
// A parameter file turned into a complete, checked configuration: plugins loaded, capabilities
// matched, every parameter validated, variables gathered and the schedule ordered. Nothing is
// allocated or written; `bhnsid check`, `schedule` and `run` all start here.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/core/params.hpp"
#include "bhnsid/core/parfile.hpp"
#include "bhnsid/core/plugin_loader.hpp"
#include "bhnsid/core/scheduler.hpp"

namespace bhnsid::core {

struct Configuration {
  ParFile file;
  std::vector<std::shared_ptr<const LoadedPlugin>> plugins;  ///< in the order of `plugins:`
  std::vector<const PluginDecl*> decls;                       ///< the core's `run` first, then the plugins
  std::map<std::string, ParamSection> params;
  std::vector<VariableSpec> variables;
  Schedule schedule;
};

Configuration configure(const std::filesystem::path& parfile, const std::vector<std::string>& overrides,
                        PluginLoader& loader);
/// Same from an already-read file (used by tests and the fuzz target).
Configuration configure(ParFile file, const std::vector<std::string>& overrides, PluginLoader& loader);

/// A parameter file holding every resolved value, which reproduces the run.
std::string resolved_parfile_yaml(const Configuration& config, const std::string& header);

/// A complete commented parameter file for these plugins, defaults and examples filled in.
std::string template_parfile_yaml(const std::vector<const PluginDecl*>& plugins);

}  // namespace bhnsid::core
