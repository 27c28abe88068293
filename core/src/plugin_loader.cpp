#include "bhnsid/core/plugin_loader.hpp"

#include <dlfcn.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <cstdlib>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/nearest.hpp"

namespace bhnsid::core {

namespace fs = std::filesystem;

std::string plugin_name_from_file(const fs::path& file) {
  const std::string base = file.filename().string();
  const std::string prefix = "libbhnsid_", suffix = ".so";
  if (base.size() <= prefix.size() + suffix.size() || base.compare(0, prefix.size(), prefix) != 0 ||
      base.compare(base.size() - suffix.size(), suffix.size(), suffix) != 0)
    return {};
  return base.substr(prefix.size(), base.size() - prefix.size() - suffix.size());
}

std::vector<fs::path> plugin_search_path(const std::vector<std::string>& extra_dirs) {
  std::vector<fs::path> path;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) path.push_back(exe.parent_path().parent_path() / "lib" / "bhnsid");
  if (const char* env = std::getenv("BHNSID_PLUGIN_PATH")) {
    std::string list = env;
    std::size_t start = 0;
    while (start <= list.size()) {
      const std::size_t colon = std::min(list.find(':', start), list.size());
      if (colon > start) path.emplace_back(list.substr(start, colon - start));
      start = colon + 1;
    }
  }
  for (const auto& dir : extra_dirs) path.emplace_back(dir);
  return path;
}

PluginLoader::PluginLoader(std::vector<fs::path> search_path) : search_path_(std::move(search_path)) {
  for (const auto& dir : search_path_) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir, ec)) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
      const std::string name = plugin_name_from_file(file);
      if (name.empty()) continue;
      if (!available_.emplace(name, file).second) shadowed_.push_back(file);
    }
  }
}

std::shared_ptr<const LoadedPlugin> PluginLoader::load(const std::string& name) {
  if (auto it = loaded_.find(name); it != loaded_.end()) return it->second;
  auto it = available_.find(name);
  if (it == available_.end()) {
    std::vector<std::string> names;
    for (const auto& [n, f] : available_) names.push_back(n);
    std::string where;
    for (const auto& dir : search_path_) where += (where.empty() ? "" : ", ") + dir.string();
    throw InputError(fmt::format("unknown plugin '{}'{}; no libbhnsid_{}.so on the plugin path ({})", name,
                                 did_you_mean(name, names), name, where.empty() ? "empty" : where));
  }
  auto plugin = load_file(it->second);
  loaded_.emplace(name, plugin);
  return plugin;
}

std::shared_ptr<const LoadedPlugin> PluginLoader::load_file(const fs::path& file) {
  const std::string path = file.string();
  // dlopen of a FIFO waits for a writer forever: only regular files (through any symlinks) are loaded.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw InputError(fmt::format("{}: cannot be loaded as a plugin: {}", path, std::strerror(errno)));
  if (!S_ISREG(st.st_mode))
    throw InputError(fmt::format("{}: is not a regular file (a FIFO, socket, device or directory); a plugin is a "
                                 "shared library file",
                                 path));
  // RTLD_LOCAL: plugins cannot see each other's symbols, so they can only meet through services.
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw InputError(fmt::format("{}: cannot be loaded as a plugin (not a valid shared library?): {}", path,
                                 why ? why : "unknown dlopen error"));
  }
  using EntryFn = const BhnsidPluginInfo* (*)();
  dlerror();
  auto entry = reinterpret_cast<EntryFn>(dlsym(handle, "bhnsid_plugin_info"));
  if (!entry)
    throw InputError(fmt::format("{}: not a bhnsid plugin: it does not export the entry point 'bhnsid_plugin_info'", path));
  const BhnsidPluginInfo* info = entry();
  if (!info) throw InputError(fmt::format("{}: the entry point returned nothing", path));
  if (info->abi_version != BHNSID_ABI_VERSION)
    throw InputError(fmt::format("{}: plugin ABI version {} does not match this bhnsid's ABI version {}; rebuild the "
                                 "plugin against this core",
                                 path, info->abi_version, BHNSID_ABI_VERSION));
  if (!info->name || !info->declare)
    throw InputError(fmt::format("{}: the plugin info has no name or no declare function", path));
  auto plugin = std::make_shared<LoadedPlugin>();
  plugin->file = file;
  plugin->decl.name = info->name;
  plugin->decl.version = info->version ? info->version : "";
  plugin->decl.description = info->description ? info->description : "";
  const std::string expected = plugin_name_from_file(file);
  if (!expected.empty() && expected != plugin->decl.name)
    throw InputError(fmt::format("{}: the file name says plugin '{}' but it declares itself '{}'", path, expected,
                                 plugin->decl.name));
  try {
    PluginBuilder builder(plugin->decl);
    info->declare(builder);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(fmt::format("{}: plugin '{}' failed while declaring itself: {}", path, plugin->decl.name, e.what()));
  }
  validate_declaration(plugin->decl);
  return plugin;
}

}  // namespace bhnsid::core
