#pragma once
// The run's checkpoints (docs/user-guide.md, "Resuming a run"): the core's state and every
// plugin's checkpoint section, after each loop iteration, in RUN_DIR/checkpoints; and the checks
// that a checkpoint belongs to this build and these parameters before a resume touches anything.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "bhnsid/core/configuration.hpp"
#include "bhnsid/core/context.hpp"
#include "bhnsid/core/log.hpp"
#include "checkpoint_file.hpp"
#include "run_state.hpp"

namespace bhnsid::core {

inline constexpr const char* checkpoint_dir_name = "checkpoints";
/// The core's own section: no plugin can bear the name (names are identifiers).
inline constexpr const char* core_section = "(core)";

/// What computes, a "PART\tVALUE" line each: the version and compiler, and a hash of the executable,
/// the core library and every loaded plugin's file; a checkpoint keeps it, so that a refusal can
/// name the part that changed. build_id_of() hashes it to the id the checkpoint is matched by.
std::string build_description(const Configuration& config);
std::string build_id_of(const std::string& description);

/// Every resolved parameter as "section.key = value" lines (and the plugin list): what must match
/// for a checkpoint to continue this run. run.max_iterations and the checkpoint settings may differ.
std::string parameter_fingerprint(const Configuration& config);

using ContextOf = std::function<Context&(const std::string& plugin)>;

/// Writes checkpoints/checkpoint.NNNNNN of state.iteration (temporary, fsync, rename) and removes
/// all but the newest two; InputError when the disk refuses.
void save_checkpoint(RunState& state, const ContextOf& context, bool converged, const std::string& build);

/// The newest checkpoint of `run_dir` that reads back whole, checked against this build and these
/// parameters (damaged ones are skipped with a warning, leftover .partial files removed); InputError
/// naming the file and the difference otherwise. Nothing of the run is touched.
struct ResumePoint {
  std::unique_ptr<CheckpointFileReader> file;
  int iteration = 0;
  bool converged = false;
};
ResumePoint find_resume_point(const std::filesystem::path& run_dir, const Configuration& config, const std::string& build,
                              const Log& log);

/// The newest checkpoint of another run (`bhnsid run --warm-start DIR`): same build, and parameters
/// that differ only where a plugin declared them steerable, or, all of those that follow the
/// spacing together, by one refinement (the next coarser run of a convergence series: grid.n half,
/// grid.dx twice this run's); InputError naming the key otherwise.
struct WarmPoint {
  std::unique_ptr<CheckpointFileReader> file;
  int iteration = 0;
  bool converged = false;
  std::string changed;  ///< "section.key old -> new, ..." for the log
  bool refined = false;  ///< the source is the next coarser run of a convergence series (its plugins interpolate)
};
WarmPoint find_warm_point(const std::filesystem::path& source_dir, const Configuration& config, const std::string& build);

/// Hands each plugin that declared a warm start its section of `file` (after INITIAL); the core's
/// own loop state (iteration, history) is not taken: the run starts its loop at iteration 1.
void apply_warm_start(RunState& state, const ContextOf& context, CheckpointFileReader& file);

/// Restores the core's loop state (iteration, history, scalars) and every plugin's section.
void restore_checkpoint(RunState& state, const ContextOf& context, CheckpointFileReader& file);

}  // namespace bhnsid::core
