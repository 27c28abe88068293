#pragma once
// Finds plugins on the plugin path and loads them with dlopen. Search order: the build's plugin
// folder (next to the executable), then BHNSID_PLUGIN_PATH, then each --plugin-path; the first
// file named libbhnsid_NAME.so wins. Loaded libraries stay loaded for the life of the process,
// because scheduled functions and services point into them.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/core/plugin.hpp"

namespace bhnsid::core {

struct LoadedPlugin {
  std::filesystem::path file;
  PluginDecl decl;
};

/// The plugin folders in search order.
std::vector<std::filesystem::path> plugin_search_path(const std::vector<std::string>& extra_dirs);

class PluginLoader {
 public:
  explicit PluginLoader(std::vector<std::filesystem::path> search_path);

  const std::vector<std::filesystem::path>& search_path() const { return search_path_; }
  /// Plugin name -> file, first match on the path; later duplicates in `shadowed()`.
  const std::map<std::string, std::filesystem::path>& available() const { return available_; }
  const std::vector<std::filesystem::path>& shadowed() const { return shadowed_; }

  /// Loads a plugin by name (InputError naming the nearest known name when there is none).
  std::shared_ptr<const LoadedPlugin> load(const std::string& name);
  /// Loads one file, checking that it is a shared library, has the entry point, the same ABI
  /// version and a valid declaration whose name matches the file name.
  static std::shared_ptr<const LoadedPlugin> load_file(const std::filesystem::path& file);

 private:
  std::vector<std::filesystem::path> search_path_;
  std::map<std::string, std::filesystem::path> available_;
  std::vector<std::filesystem::path> shadowed_;
  std::map<std::string, std::shared_ptr<const LoadedPlugin>> loaded_;
};

/// "libbhnsid_grid.so" -> "grid"; "" for other file names.
std::string plugin_name_from_file(const std::filesystem::path& file);

}  // namespace bhnsid::core
