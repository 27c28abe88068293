// The bhnsid command line: parse with CLI11, hand off to a subcommand, turn typed errors into
// one message and an exit code (2 for bad input, 1 for a failed run, 3 for an internal error).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <iostream>
#include <unistd.h>

#include "bhnsid/core/build_info.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/interrupt.hpp"
#include "commands.hpp"

using namespace bhnsid;

namespace {
std::string shell_quote(const std::string& arg) {
  if (!arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=:,[]") ==
                          std::string::npos)
    return arg;
  std::string out = "'";
  for (char c : arg) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}
// The one error line, best effort: a stderr that cannot be written (a full disk, a closed pipe)
// must not turn a clean exit code into an abort.
// One line, whatever a name in it holds: a newline in a --set key or a NUL in a file is shown as \xNN.
void complain(const std::string& line) {
  std::string out;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    const bool last_newline = c == '\n' && i + 1 == line.size();
    out += (c < 0x20 && !last_newline) || c == 0x7f ? fmt::format("\\x{:02x}", c) : std::string(1, line[i]);
  }
  std::fputs(out.c_str(), stderr);
}

// `bhnsid NAME ARGS...` for a NAME that is no built-in command runs `bhnsid-NAME ARGS...` from
// the executable's folder, git-style: tools built beside bhnsid (bhnsid-export, of the reader)
// join the command line without the core knowing them. Returns only when there is none.
void run_external(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-' || std::string(argv[1]).find('/') != std::string::npos) return;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return;
  const std::filesystem::path tool = exe.parent_path() / (std::string("bhnsid-") + argv[1]);
  if (::access(tool.c_str(), X_OK) != 0) return;
  std::fflush(stdout);
  argv[1] = const_cast<char*>(tool.c_str());
  ::execv(tool.c_str(), argv + 1);
  complain(fmt::format("bhnsid: error: cannot run {}: {}\n", tool.string(), std::strerror(errno)));
  std::exit(core::exit_internal);
}
}  // namespace

int main(int argc, char** argv) {
  // A full disk or a file-size limit must reach us as a write error, not kill the process.
  std::signal(SIGXFSZ, SIG_IGN);
  static const char* const builtin[] = {"run", "check", "schedule", "params", "plugins", "validate", "plot"};
  if (argc >= 2 && argv[1][0] != '-' &&
      std::none_of(std::begin(builtin), std::end(builtin), [&](const char* c) { return std::string(c) == argv[1]; })) {
    run_external(argc, argv);
    complain(fmt::format("bhnsid: error: unknown command '{}'; expected one of {} or a tool bhnsid-{} beside the "
                         "executable (bhnsid --help)\n",
                         argv[1], fmt::join(std::begin(builtin), std::end(builtin), ", "), argv[1]));
    return core::exit_input;
  }

  cli::CommonOptions common;
  for (int i = 0; i < argc; ++i) common.command_line += (i ? " " : "") + shell_quote(argv[i]);

  CLI::App app{"bhnsid: general-relativistic initial data for black hole-neutron star binaries"};
  app.set_version_flag("--version", fmt::format("bhnsid {} ({}, {})", core::build_version(),
                                                core::build_git_revision(), core::build_type()));
  app.require_subcommand(1);
  const auto add_plugin_path = [&](CLI::App* sub) {
    sub->add_option("--plugin-path", common.plugin_dirs, "extra plugin folder, searched after the build's and BHNSID_PLUGIN_PATH (repeatable)")
        ->allow_extra_args(false);  // one folder per flag, so a following parameter file stays positional
  };
  std::string parfile, output, warm_start;
  bool force = false, resume = false, yaml = false, verbose = false;
  std::vector<std::string> plugin_names;

  auto* run = app.add_subcommand("run", "validate, then run a parameter file and write its run directory");
  run->add_option("parfile", parfile, "parameter file (YAML)")->required();
  run->add_option("--set", common.overrides, "override a parameter: section.key=value (repeatable)")->allow_extra_args(false);
  run->add_option("--output", output, "run directory (default runs/<parfile stem>)");
  run->add_flag("--force", force, "replace an existing run directory");
  run->add_flag("--resume", resume,
                "continue the run in the run directory from its newest checkpoint (same parameters and build; "
                "run.max_iterations may grow)")
      ->excludes("--force");
  run->add_option("--warm-start", warm_start,
                  "start from the newest checkpoint of another run directory of this build whose parameters differ "
                  "only in steerable ones (the previous run of a parameter scan) or by one refinement of the lattice "
                  "(the next coarser run of a convergence series)")
      ->excludes("--resume");
  run->add_flag("--verbose", verbose, "print log.txt's detail lines too (every multigrid cycle, every plugin step)");
  add_plugin_path(run);

  auto* check = app.add_subcommand("check", "validate a parameter file completely without running it (exit 0 or 2)");
  check->add_option("parfile", parfile, "parameter file (YAML)")->required();
  check->add_option("--set", common.overrides, "override a parameter: section.key=value (repeatable)")->allow_extra_args(false);
  add_plugin_path(check);

  auto* schedule = app.add_subcommand("schedule", "print the ordered schedule of a parameter file without running");
  schedule->add_option("parfile", parfile, "parameter file (YAML)")->required();
  schedule->add_option("--set", common.overrides, "override a parameter: section.key=value (repeatable)")->allow_extra_args(false);
  add_plugin_path(schedule);

  auto* params = app.add_subcommand("params", "print every parameter (type, default, range, doc) of plugins");
  params->add_option("plugins", plugin_names, "plugins to describe (default: all on the plugin path)");
  params->add_flag("--yaml", yaml, "print a complete commented parameter file for these plugins instead");
  add_plugin_path(params);

  cli::ValidateOptions vopt;
  auto* validate = app.add_subcommand(
      "validate", "run a parameter file at dx, dx/2, dx/4 on the same cube with the independent residual evaluator and "
                  "report each equation's convergence order (exit 1 below the threshold)");
  validate->add_option("parfile", parfile, "parameter file (YAML)")->required();
  validate->add_option("--levels", vopt.levels, "resolutions: dx, dx/2, ... (default 3)");
  validate->add_option("--threshold", vopt.threshold, "smallest accepted order of the L2 residual at the finest pair (default 1.8)");
  validate->add_option("--set", common.overrides, "override a parameter: section.key=value (repeatable)")->allow_extra_args(false);
  validate->add_option("--output", vopt.output, "directory (default runs/<parfile stem>_validate)");
  validate->add_flag("--force", vopt.force, "replace an existing validate directory");
  validate->add_flag("!--no-plots", vopt.plots, "skip the PNG plots (python3 with matplotlib)");
  validate->add_option("--only", vopt.only,
                       "judge only these of the equations the evaluator reports, e.g. for manufactured "
                       "configurations that satisfy one equation; the others are reported")
      ->allow_extra_args(false);
  validate->add_option("--with", vopt.with,
                       "add a plugin to the file's list (repeatable), e.g. the residual evaluator when the file has none")
      ->allow_extra_args(false);
  add_plugin_path(validate);

  auto* plugins = app.add_subcommand("plugins", "list the plugins on the plugin path");
  add_plugin_path(plugins);

  std::string run_dir, plot_output;
  auto* plot = app.add_subcommand("plot", "PNG pictures of a run: every plugin of the run that ships a plot script draws its part");
  plot->add_option("run_dir", run_dir, "a run directory (of bhnsid run)")->required();
  plot->add_option("--output", plot_output, "folder for the pictures (default RUN_DIR/plots)");
  add_plugin_path(plot);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return core::exit_input;
  }

  try {
    // An empty name would silently become the default directory.
    if ((run->parsed() && run->count("--output") && output.empty()) ||
        (validate->parsed() && validate->count("--output") && vopt.output.empty()) ||
        (plot->parsed() && plot->count("--output") && plot_output.empty()))
      throw core::InputError("--output: expected a directory name, got an empty string");
    // A run's results are its files: a signal stops it at a safe point and a closed terminal pipe
    // must not fail it. Every other command's result is what it prints: the signals keep their
    // default actions (`bhnsid params | head` ends quietly) and a failed write is an error.
    if (run->parsed() || validate->parsed()) core::install_interrupt_handlers();
    if (run->parsed()) return cli::cmd_run(parfile, common, output, force, resume, warm_start, verbose);
    if (validate->parsed()) return cli::cmd_validate(parfile, common, vopt);
    int code = core::exit_internal;
    try {
      if (check->parsed()) code = cli::cmd_check(parfile, common);
      if (schedule->parsed()) code = cli::cmd_schedule(parfile, common);
      if (params->parsed()) code = cli::cmd_params(plugin_names, yaml, common);
      if (plugins->parsed()) code = cli::cmd_plugins(common);
      if (plot->parsed()) code = cli::cmd_plot(run_dir, plot_output, common);
      if (std::fflush(stdout) != 0 || std::ferror(stdout))
        throw std::system_error(errno, std::generic_category(), "standard output");
    } catch (const std::filesystem::filesystem_error&) {
      throw;
    } catch (const std::system_error& e) {
      // fmt::print reports a failed write this way (a full disk).
      complain(fmt::format("bhnsid: error: cannot write the output: {}\n", e.what()));
      return core::exit_input;
    }
    return code;
  } catch (const std::filesystem::filesystem_error& e) {
    // A folder or file the system refused: it names the path and the reason.
    complain(fmt::format("bhnsid: error: {}\n", e.what()));
    return core::exit_input;
  } catch (const core::InputError& e) {
    complain(fmt::format("bhnsid: error: {}\n", e.what()));
    return core::exit_input;
  } catch (const core::Interrupted& e) {
    complain(fmt::format("bhnsid: {}\n", e.what()));
    return 128 + core::interrupt_signal();
  } catch (const core::RunFailure& e) {
    complain(fmt::format("bhnsid: run failed: {}\n", e.what()));
    return core::exit_run_failed;
  } catch (const std::exception& e) {
    complain(fmt::format("bhnsid: internal error: {}\n", e.what()));
    return core::exit_internal;
  }
  return core::exit_internal;
}
