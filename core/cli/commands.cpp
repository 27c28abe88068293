#include "commands.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>

#include "bhnsid/core/configuration.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/run.hpp"

namespace bhnsid::cli {

using namespace bhnsid::core;
namespace fs = std::filesystem;

namespace {
PluginLoader make_loader(const CommonOptions& common) { return PluginLoader(plugin_search_path(common.plugin_dirs)); }

std::string joined(const std::vector<std::string>& words) {
  return words.empty() ? std::string("-") : fmt::format("{}", fmt::join(words, ", "));
}

void print_params(const PluginDecl& decl) {
  fmt::print("{} ({}): {}\n", decl.name, decl.version, decl.description);
  if (decl.params.empty()) fmt::print("  (no parameters)\n");
  for (const auto& p : decl.params) {
    fmt::print("  {:<22} {:<11} {:<24} {}\n", p.name, to_string(p.type),
               p.required() ? "REQUIRED" : "default " + format_value(*p.default_value), describe_range(p));
    const char* refines = p.refinement == Refinement::doubles  ? " [doubles per halving of the spacing in validate]"
                          : p.refinement == Refinement::halves ? " [halves with the spacing in validate]"
                                                               : "";
    fmt::print("  {:<22} {}{}{}\n", "", p.doc, p.steerable ? " [steerable]" : "", refines);
  }
}
}  // namespace

int cmd_run(const std::string& parfile, const CommonOptions& common, const std::string& output, bool force, bool resume,
            const std::string& warm_start, bool verbose) {
  PluginLoader loader = make_loader(common);
  const Configuration config = configure(parfile, common.overrides, loader);
  RunOptions options;
  options.run_directory = output.empty() ? fs::path("runs") / fs::path(parfile).stem() : fs::path(output);
  options.force = force;
  options.resume = resume;
  options.warm_start = warm_start;
  // --force replaces the run directory: never the one the warm start reads.
  std::error_code ec;
  if (!warm_start.empty() && fs::exists(options.run_directory, ec) &&
      fs::equivalent(fs::path(warm_start), options.run_directory, ec))
    throw InputError(fmt::format("--warm-start {}: is the run directory of this run; warm-start from another run",
                                       warm_start));
  options.verbose = verbose;
  options.command_line = common.command_line;
  options.protect.push_back(fs::path(parfile));
  const RunResult result = run(config, options);
  return result.exit_code;
}

int cmd_check(const std::string& parfile, const CommonOptions& common) {
  PluginLoader loader = make_loader(common);
  const Configuration config = configure(parfile, common.overrides, loader);
  const MemoryEstimate memory = check_parameters(config);
  std::size_t entries = 0, params = 0;
  for (const auto& [bin, list] : config.schedule) entries += list.size();
  for (const auto& [name, section] : config.params) params += section.values().size();
  const MemoryLimit limit = available_memory();
  fmt::print("{}: OK ({} plugins, {} parameters, {} scheduled entries)\n", parfile, config.plugins.size(), params,
             entries);
  fmt::print("memory: estimated {} of {} available ({})\n", format_bytes(memory.total()), format_bytes(limit.bytes),
             limit.source);
  for (const auto& item : memory.items())
    fmt::print("  {:<18} {:>10}  {}\n", item.plugin, format_bytes(item.bytes), item.what);
  return exit_ok;
}

int cmd_schedule(const std::string& parfile, const CommonOptions& common) {
  PluginLoader loader = make_loader(common);
  const Configuration config = configure(parfile, common.overrides, loader);
  fmt::print("{}", format_schedule(config.schedule));
  return exit_ok;
}

int cmd_params(const std::vector<std::string>& plugins, bool yaml, const CommonOptions& common) {
  PluginLoader loader = make_loader(common);
  std::vector<std::string> names = plugins;
  if (names.empty())
    for (const auto& [name, file] : loader.available()) names.push_back(name);
  std::vector<std::shared_ptr<const LoadedPlugin>> loaded;
  std::vector<const PluginDecl*> decls{&core_declaration()};
  for (const auto& name : names) {
    if (name == core_declaration().name) continue;
    loaded.push_back(loader.load(name));
    decls.push_back(&loaded.back()->decl);
  }
  if (yaml) {
    fmt::print("{}", template_parfile_yaml(decls));
    return exit_ok;
  }
  for (const auto* decl : decls) {
    if (!plugins.empty() && decl == &core_declaration() &&
        std::find(plugins.begin(), plugins.end(), decl->name) == plugins.end())
      continue;
    print_params(*decl);
    fmt::print("\n");
  }
  return exit_ok;
}

int cmd_plugins(const CommonOptions& common) {
  PluginLoader loader = make_loader(common);
  fmt::print("plugin path:\n");
  for (const auto& dir : loader.search_path()) fmt::print("  {}\n", dir.string());
  fmt::print("\n");
  int broken = 0;
  for (const auto& [name, file] : loader.available()) {
    try {
      const auto plugin = PluginLoader::load_file(file);
      const auto& d = plugin->decl;
      fmt::print("{:<24} {}\n", d.name + " " + d.version, d.description);
      fmt::print("{:<24} implements: {}; requires: {}\n", "", joined(d.implements), joined(d.requires_caps));
      fmt::print("{:<24} {}\n", "", file.string());
    } catch (const InputError& e) {
      ++broken;
      fmt::print("{:<24} BROKEN: {}\n", name, e.what());
    }
  }
  for (const auto& file : loader.shadowed()) fmt::print("(shadowed by an earlier folder: {})\n", file.string());
  if (loader.available().empty()) fmt::print("(no plugins found)\n");
  return broken ? exit_input : exit_ok;
}

}  // namespace bhnsid::cli
