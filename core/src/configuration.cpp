#include "bhnsid/core/configuration.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::core {

namespace {

void check_capabilities(const Configuration& config, const PluginLoader& loader) {
  std::map<std::string, std::string> provider;
  for (const auto& p : config.plugins)
    for (const auto& cap : p->decl.implements) {
      auto [it, inserted] = provider.emplace(cap, p->decl.name);
      if (!inserted)
        throw InputError(fmt::format("{}: plugins '{}' and '{}' both implement capability '{}'; keep only one of them",
                                     config.file.source, it->second, p->decl.name, cap));
    }
  for (const auto& p : config.plugins)
    for (const auto& cap : p->decl.requires_caps)
      if (!provider.count(cap)) {
        // Say which plugins on the path could fill the gap; loading them is cheap and side-effect free.
        std::vector<std::string> candidates;
        for (const auto& [name, file] : loader.available()) {
          try {
            const auto candidate = PluginLoader::load_file(file);
            for (const auto& c : candidate->decl.implements)
              if (c == cap) candidates.push_back(name);
          } catch (const InputError&) {
          }
        }
        throw InputError(fmt::format("{}: plugin '{}' requires capability '{}', which no active plugin implements{}",
                                     config.file.source, p->decl.name, cap,
                                     candidates.empty() ? std::string{}
                                                        : fmt::format("; add one of: {}", fmt::join(candidates, ", "))));
      }
}

void gather_variables(Configuration& config) {
  for (const auto& p : config.plugins)
    for (const auto& v : p->decl.variables) {
      for (const auto& other : config.variables)
        if (other.name == v.name)
          throw InputError(fmt::format("{}: plugins '{}' and '{}' both declare grid variable '{}'", config.file.source,
                                       other.plugin, v.plugin, v.name));
      config.variables.push_back(v);
    }
}

}  // namespace

Configuration configure(const std::filesystem::path& parfile, const std::vector<std::string>& overrides,
                        PluginLoader& loader) {
  return configure(load_parfile(parfile), overrides, loader);
}

Configuration configure(ParFile file, const std::vector<std::string>& overrides, PluginLoader& loader) {
  Configuration config;
  config.file = std::move(file);
  for (const auto& assignment : overrides) apply_override(config.file, assignment);
  config.decls.push_back(&core_declaration());
  for (std::size_t i = 0; i < config.file.plugins.size(); ++i) {
    const std::string& name = config.file.plugins[i];
    if (name == core_declaration().name)
      throw InputError(fmt::format("{}: plugins: '{}' is the core's own section, not a plugin",
                                   config.file.plugin_pos[i].str(), name));
    try {
      config.plugins.push_back(loader.load(name));
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", config.file.plugin_pos[i].str(), e.what()));
    }
    config.decls.push_back(&config.plugins.back()->decl);
  }
  check_capabilities(config, loader);
  std::vector<std::string> inactive;
  for (const auto& [name, f] : loader.available())
    if (std::find(config.file.plugins.begin(), config.file.plugins.end(), name) == config.file.plugins.end())
      inactive.push_back(name);
  config.params = resolve_params(config.file, config.decls, inactive);
  gather_variables(config);
  try {
    config.schedule = build_schedule(config.decls);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", config.file.source, e.what()));
  }
  return config;
}

namespace {
std::string comment_lines(const ParamSpec& spec) {
  std::string text = fmt::format("  # {} [{}; {}]{}{}\n", spec.doc, to_string(spec.type), describe_range(spec),
                                 spec.required() ? " REQUIRED (example value below)" : "",
                                 spec.steerable ? " steerable" : "");
  return text;
}
}  // namespace

std::string resolved_parfile_yaml(const Configuration& config, const std::string& header) {
  std::string out = header;
  out += fmt::format("plugins: [{}]\n", fmt::join(config.file.plugins, ", "));
  for (const auto* decl : config.decls) {
    const auto& section = config.params.at(decl->name);
    if (decl->params.empty()) continue;
    out += fmt::format("{}:\n", decl->name);
    for (const auto& spec : decl->params)
      out += fmt::format("  {}: {}\n", spec.name, format_value(section.values().at(spec.name)));
  }
  return out;
}

std::string template_parfile_yaml(const std::vector<const PluginDecl*>& plugins) {
  std::string out = "# bhnsid parameter file: every parameter, with its default or an example value.\n";
  std::vector<std::string> names;
  for (const auto* d : plugins)
    if (d->name != core_declaration().name) names.push_back(d->name);
  out += fmt::format("plugins: [{}]\n", fmt::join(names, ", "));
  for (const auto* decl : plugins) {
    if (decl->params.empty()) continue;
    out += fmt::format("\n# {}: {}\n{}:\n", decl->name, decl->description, decl->name);
    for (const auto& spec : decl->params) {
      out += comment_lines(spec);
      out += fmt::format("  {}: {}\n", spec.name, format_value(spec.required() ? *spec.example : *spec.default_value));
    }
  }
  return out;
}

}  // namespace bhnsid::core
