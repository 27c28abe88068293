#pragma once
// The subcommands of the bhnsid executable; each returns the process exit code.
#include <string>
#include <vector>

namespace bhnsid::cli {

struct CommonOptions {
  std::vector<std::string> plugin_dirs;
  std::vector<std::string> overrides;
  std::string command_line;
};

int cmd_run(const std::string& parfile, const CommonOptions& common, const std::string& output, bool force);
int cmd_check(const std::string& parfile, const CommonOptions& common);
int cmd_schedule(const std::string& parfile, const CommonOptions& common);
int cmd_params(const std::vector<std::string>& plugins, bool yaml, const CommonOptions& common);
int cmd_plugins(const CommonOptions& common);

}  // namespace bhnsid::cli
