#pragma once
// Executes a configuration: creates the run directory, runs the bins in order, keeps the last state
// on failure and writes params.yaml, log.txt, timers.tsv, scalars.tsv and summary.json.
#include <filesystem>
#include <string>
#include <vector>

#include "bhnsid/core/configuration.hpp"
#include "bhnsid/core/memory.hpp"

namespace bhnsid::core {

struct RunOptions {
  std::filesystem::path run_directory;
  bool force = false;
  bool resume = false;  ///< continue the run in run_directory from its newest checkpoint (bhnsid run --resume)
  /// A run of the same build (converged or not: the log says which) whose parameters differ only in
  /// steerable ones, or by one refinement of the lattice (the next coarser run): each plugin that declared a warm start takes its state from that run's newest
  /// checkpoint (bhnsid run --warm-start).
  std::filesystem::path warm_start;
  std::string command_line;
  bool verbose = false;  ///< detail lines (per multigrid cycle, per plugin step) on the terminal too
  std::vector<std::filesystem::path> protect;  ///< --force never replaces a directory holding one (the parameter file)
};

struct RunResult {
  std::string status;  ///< "converged", "completed", "failed" or "interrupted"
  int iterations = 0;
  int exit_code = 0;
  double memory_estimate = 0;  ///< bytes, from check_parameters
};

/// Runs every PARAMCHECK entry (cross-parameter checks that read parameters only; no run
/// directory), bounds run.threads, then sums every plugin's memory estimate and refuses a run
/// that cannot fit in the memory this process may use: `bhnsid check` and, before anything is
/// written, `bhnsid run`. A failure is an InputError naming the file and the entry or key.
MemoryEstimate check_parameters(const Configuration& config);

/// What the process needs beyond its plugins' estimates (code, libraries, stacks, the allocator),
/// measured as the peak resident size of a run with a tiny grid, 12-18 MiB (docs/reliability.md).
inline constexpr double process_base_bytes = 32.0 * 1024 * 1024;

RunResult run(const Configuration& config, const RunOptions& options);

/// Build and host facts for summary.json's "provenance".
struct Provenance {
  std::string version, git_revision, build_type, compiler, host, date, command_line;
};
Provenance provenance(const std::string& command_line);

}  // namespace bhnsid::core
