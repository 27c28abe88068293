// bhnsid plot RUN_DIR: runs the plot script that each plugin of the run ships beside its library
// (NAME.plot.py, bhnsid_add_plugin(... PLOT script.py)) as `python3 SCRIPT RUN_DIR OUTPUT_DIR`. The
// core knows neither the fields nor the pictures: a plugin that owns the physics draws it.
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/parfile.hpp"
#include "bhnsid/core/plugin_loader.hpp"
#include "commands.hpp"

namespace bhnsid::cli {

namespace fs = std::filesystem;

namespace {

/// Runs argv (no shell: the paths are passed as they are); the exit status, or -1 if it did not start.
int run_process(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

int cmd_plot(const std::string& run_dir, const std::string& output, const CommonOptions& common) {
  const fs::path run(run_dir);
  if (!fs::is_regular_file(run / "params.yaml"))
    throw core::InputError(fmt::format("{}: not a run directory (no params.yaml); expected the directory of a "
                                       "`bhnsid run`",
                                       run_dir));
  const core::ParFile file = core::load_parfile(run / "params.yaml");
  core::PluginLoader loader(core::plugin_search_path(common.plugin_dirs));
  const fs::path out = output.empty() ? run / "plots" : fs::path(output);
  // Debian's interpreter, where matplotlib and h5py are installed (scripts/install-deps.sh).
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  int scripts = 0, failed = 0;
  for (const std::string& name : file.plugins) {
    const auto found = loader.available().find(name);
    if (found == loader.available().end()) continue;
    const fs::path script = found->second.parent_path() / (name + ".plot.py");
    if (!fs::exists(script)) continue;
    if (scripts++ == 0) fs::create_directories(out);
    std::printf("plot: %s\n", name.c_str());
    std::fflush(stdout);
    const int code = run_process({python, script.string(), run.string(), out.string()});
    if (code != 0) {
      ++failed;
      std::fprintf(stderr, "plot: %s's plot script (%s) failed with status %d\n", name.c_str(), script.c_str(), code);
    }
  }
  if (scripts == 0)
    throw core::InputError(fmt::format("{}: none of the run's plugins ({}) ships a plot script", run_dir,
                                       fmt::join(file.plugins, ", ")));
  std::printf("plot: %d of %d plot script(s) succeeded; pictures in %s\n", scripts - failed, scripts, out.c_str());
  return failed == 0 ? core::exit_ok : core::exit_run_failed;
}

}  // namespace bhnsid::cli
