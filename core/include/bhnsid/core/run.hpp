#pragma once
// Executes a configuration: creates the run directory, runs the bins in order, keeps the last state
// on failure and writes params.yaml, log.txt, timers.tsv, history.tsv and summary.json.
#include <filesystem>
#include <string>

#include "bhnsid/core/configuration.hpp"

namespace bhnsid::core {

struct RunOptions {
  std::filesystem::path run_directory;
  bool force = false;
  std::string command_line;
};

struct RunResult {
  std::string status;  ///< "converged", "completed" or "failed"
  int iterations = 0;
  int exit_code = 0;
};

/// Runs every PARAMCHECK entry (cross-parameter checks that read parameters only; no services,
/// no run directory): `bhnsid check` and, before anything is written, `bhnsid run`. A failure is
/// an InputError naming the entry.
void check_parameters(const Configuration& config);

RunResult run(const Configuration& config, const RunOptions& options);

/// Build and host facts for summary.json's "provenance".
struct Provenance {
  std::string version, git_revision, build_type, compiler, host, date, command_line;
};
Provenance provenance(const std::string& command_line);

}  // namespace bhnsid::core
