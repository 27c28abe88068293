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

int cmd_run(const std::string& parfile, const CommonOptions& common, const std::string& output, bool force, bool resume,
            const std::string& warm_start, bool verbose);
int cmd_check(const std::string& parfile, const CommonOptions& common);
int cmd_schedule(const std::string& parfile, const CommonOptions& common);
int cmd_params(const std::vector<std::string>& plugins, bool yaml, const CommonOptions& common);
int cmd_plugins(const CommonOptions& common);
/// Runs the plot script of every plugin of the run that ships one (NAME.plot.py beside its library).
int cmd_plot(const std::string& run_dir, const std::string& output, const CommonOptions& common);

/// Most resolutions of one validate series: the finest has 8^(levels - 1) times the points of the first.
inline constexpr int max_validate_levels = 8;

struct ValidateOptions {
  int levels = 3;
  double threshold = 1.8;
  std::string output;
  bool force = false;
  bool plots = true;
  std::vector<std::string> only;  ///< judge only these equations (all others are reported); empty: all
  std::vector<std::string> with;  ///< plugins added to the file's list (e.g. a residual evaluator)
};
/// Runs the parameter file at dx, dx/2, ... (the refined parameters of its plugins, same cube) with
/// its residual evaluator plugin (core/residual_report.hpp), prints each
/// equation's residual norms and convergence orders, writes validate.json (and PNG plots); exit 0
/// when every judged equation converges at least at `threshold`, 1 otherwise.
int cmd_validate(const std::string& parfile, const CommonOptions& common, const ValidateOptions& options);

}  // namespace bhnsid::cli
