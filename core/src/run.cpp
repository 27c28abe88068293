#include "bhnsid/core/run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <algorithm>
#include <fstream>
#include <memory>
#include <sstream>
#include <cmath>
#include <thread>
#include <nlohmann/json.hpp>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "bhnsid/core/atomic_file.hpp"
#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/interrupt.hpp"
#include "bhnsid/core/owned_entry.hpp"
#include "bhnsid/core/run_directory.hpp"
#include "run_checkpoint.hpp"
#include "run_state.hpp"

namespace bhnsid::core {

namespace {

struct Timer {
  std::string bin, entry;
  long calls = 0;
  double seconds = 0;
};

// Runs the bins and records timings; a failure is remembered, not rethrown, so the bins that keep
// the last state still run.
class Executor {
 public:
  explicit Executor(RunState& state) : state_(state), log_(&state.sink, "") {
    for (const auto* decl : state.config.decls) contexts_.emplace(decl->name, Context(state, *decl));
  }

  /// False when an entry failed or, with `interruptible`, a stopping signal arrived: the safe
  /// points are between entries.
  bool run_bin(Bin bin, bool interruptible = true) {
    auto it = state_.config.schedule.find(bin);
    if (it == state_.config.schedule.end()) return true;
    for (const auto* entry : it->second) {
      if (interruptible && interrupted()) return false;
      if (!call(*entry, [&](Context& ctx) { entry->fn(ctx); })) return false;
    }
    return !(interruptible && interrupted());
  }

  /// SOLVE; with `keep`, a StepFailure does not fail the run but is returned in `step_failure`
  /// (empty otherwise), for the loop to retreat.
  bool run_solve(bool keep, std::string& step_failure) {
    keep_step_failures_ = keep;
    step_failure_.clear();
    const bool ok = run_bin(Bin::solve);
    keep_step_failures_ = false;
    step_failure = step_failure_;
    return ok;
  }

  /// Latches the first stopping signal, with where the run stood.
  bool interrupted() {
    if (signal_ == 0 && interrupt_signal() != 0) {
      signal_ = interrupt_signal();
      log_.warn("{} received: stopping at iteration {}; the last state is kept", signal_name(signal_), state_.iteration);
    }
    return signal_ != 0;
  }
  int signal() const { return signal_; }

  /// Returns false when a CHECK entry failed outright; `all_converged` and `detail` report the rest.
  bool run_checks(bool& all_converged, std::string& detail, std::vector<std::string>& waiting) {
    all_converged = true;
    detail.clear();
    waiting.clear();
    auto it = state_.config.schedule.find(Bin::check);
    if (it == state_.config.schedule.end()) return true;
    for (const auto* entry : it->second) {
      if (interrupted()) return false;
      Convergence result;
      if (!call(*entry, [&](Context& ctx) { result = entry->check(ctx); })) return false;
      all_converged = all_converged && result.converged;
      if (!result.converged) waiting.push_back(entry->full_name());
      detail += fmt::format("{}{}: {}{}", detail.empty() ? "" : "; ", entry->full_name(),
                            result.converged ? "converged" : "not converged",
                            result.detail.empty() ? "" : " (" + result.detail + ")");
    }
    return true;
  }

  Context& context(const std::string& plugin) { return contexts_.at(plugin); }
  const std::vector<Timer>& timers() const { return timers_; }
  const std::string& failure() const { return state_.failure; }
  int failure_code() const { return failure_code_; }
  void fail(const std::string& message, int code) {
    if (state_.failure.empty()) {
      state_.failure = message;  // also what Context::run_record() reports
      failure_code_ = code;
    }
    log_.warn("run failed: {}", message);
  }

 private:
  template <class F>
  bool call(const ScheduleEntry& entry, F&& body) {
    Timer& timer = timer_for(entry);
    const auto start = std::chrono::steady_clock::now();
    bool ok = true;
    // Inside the loop the failure names its iteration: a long outer iteration fails late.
    const std::string where =
        state_.in_loop ? fmt::format("{} (iteration {})", entry.full_name(), state_.iteration) : entry.full_name();
    try {
      body(contexts_.at(entry.plugin));
    } catch (const StepFailure& e) {
      // Kept apart while a retreat may follow; the loop decides whether it fails the run.
      if (keep_step_failures_)
        step_failure_ = fmt::format("{}: {}", where, e.what());
      else
        fail(fmt::format("{}: {}", where, e.what()), exit_run_failed);
      ok = false;
    } catch (const RunFailure& e) {
      fail(fmt::format("{}: {}", where, e.what()), exit_run_failed);
      ok = false;
    } catch (const InputError& e) {
      fail(fmt::format("{}: {}", where, e.what()), exit_input);
      ok = false;
    } catch (const std::exception& e) {
      fail(fmt::format("{}: internal error: {}", where, e.what()), exit_internal);
      ok = false;
    }
    timer.calls += 1;
    timer.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return ok;
  }

  Timer& timer_for(const ScheduleEntry& entry) {
    for (auto& t : timers_)
      if (t.entry == entry.full_name()) return t;
    timers_.push_back(Timer{to_string(entry.bin), entry.full_name()});
    return timers_.back();
  }

  RunState& state_;
  Log log_;
  std::map<std::string, Context> contexts_;
  std::vector<Timer> timers_;
  int failure_code_ = 0;
  bool keep_step_failures_ = false;
  std::string step_failure_;
  int signal_ = 0;
};

// SOLVE; after a StepFailure, RETREAT (each plugin undoes the last UPDATE and what the failed solve
// left), UPDATE again with half the step, SOLVE again, at most `max_retreats` times (physics-notes'
// fold guard: "halve (sigma - sigma_old) and retry"). Returns the retreats taken, or -1 on failure.
int solve_with_retreats(Executor& exec, const Log& log, RunState& state, int max_retreats) {
  std::string step_failure;
  bool ok = exec.run_solve(max_retreats > 0, step_failure);
  int retreats = 0;
  while (!ok && !step_failure.empty()) {
    if (retreats == max_retreats) {
      exec.fail(fmt::format("{} (the outer step was halved {} times first, run.max_retreats = {})", step_failure, retreats,
                            max_retreats),
                exit_run_failed);
      break;
    }
    ++retreats;
    state.step_fraction *= 0.5;
    log.warn("{}; retreat {} of at most {}: the last update is undone and taken again at {} of its step", step_failure,
             retreats, max_retreats, state.step_fraction);
    // Cleared first: a RETREAT or UPDATE that fails, or a signal, ends the loop as what it is.
    step_failure.clear();
    ok = exec.run_bin(Bin::retreat) && exec.run_bin(Bin::update) && exec.run_solve(true, step_failure);
  }
  // The next update is a full step again: backtrack only on failure.
  state.step_fraction = 1;
  return ok ? retreats : -1;
}

bool has_loop(const Schedule& schedule) {
  return schedule.count(Bin::solve) || schedule.count(Bin::update) || schedule.count(Bin::check);
}

std::string timers_tsv(const std::vector<Timer>& timers, double total) {
  std::string out = "bin\tentry\tcalls\tseconds\n";
  for (const auto& t : timers) out += fmt::format("{}\t{}\t{}\t{:.6f}\n", t.bin, t.entry, t.calls, t.seconds);
  return out + fmt::format("TOTAL\ttotal\t1\t{:.6f}\n", total);
}

// One row per loop iteration: what each plugin set, and the iteration's wall time (the core's own
// column, `seconds`).
std::string scalars_tsv(const RunState& state) {
  std::string out = "iteration";
  for (const auto& c : state.history_columns) out += "\t" + c;
  out += "\n";
  for (std::size_t i = 0; i < state.history.size(); ++i) {
    out += fmt::format("{}", i + 1);
    for (const auto& c : state.history_columns) {
      auto it = state.history[i].find(c);
      out += it == state.history[i].end() ? std::string("\t") : fmt::format("\t{:.17g}", it->second);
    }
    out += "\n";
  }
  return out;
}

std::string summary_json(const RunState& state, const RunResult& result, const std::string& message,
                         const Provenance& p) {
  nlohmann::ordered_json j;
  j["status"] = result.status;
  j["iterations"] = result.iterations;
  j["memory_estimate_bytes"] = result.memory_estimate;
  if (!message.empty()) j["message"] = message;
  j["scalars"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : state.scalars) {
    // JSON has no NaN: a non-finite scalar is written as null, which no reader mistakes for a number.
    if (std::isfinite(value))
      j["scalars"][name] = value;
    else
      j["scalars"][name] = nullptr;
  }
  j["provenance"] = {{"version", p.version},   {"git_revision", p.git_revision}, {"build_type", p.build_type},
                     {"compiler", p.compiler}, {"host", p.host},                 {"date", p.date},
                     {"command_line", p.command_line}};
  // A name holding bytes that are not UTF-8 (a directory called \xff) is kept, replaced by U+FFFD.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace

namespace {

// Oversubscribing the cores only slows every kernel down, and libgomp fails outright (a segfault
// creating the thread pool) somewhere above a few thousand threads.
void check_threads(const Configuration& config) {
  const std::int64_t threads = config.params.at("run").integer("threads");
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::int64_t most = 4 * static_cast<std::int64_t>(cores);
  if (threads > most)
    throw InputError(fmt::format("{}: run.threads = {}: expected at most {} (4 x the {} cores of this machine); more "
                                 "threads than cores only slow the solve down, and the OpenMP runtime cannot create "
                                 "thousands",
                                 config.file.source, threads, most, cores));
}

const PluginDecl& decl_of(const Configuration& config, const std::string& plugin) {
  for (const auto* d : config.decls)
    if (d->name == plugin) return *d;
  throw std::logic_error("schedule entry of an unknown plugin " + plugin);
}

}  // namespace

MemoryEstimate check_parameters(const Configuration& config) {
  check_threads(config);
  RunState state(config);
  auto it = config.schedule.find(Bin::paramcheck);
  if (it != config.schedule.end())
    for (const auto* entry : it->second) {
      Context ctx(state, decl_of(config, entry->plugin));
      // A parameter combination that cannot run is bad input, whoever finds it; the message
      // names the file, and the plugin's message the key.
      try {
        entry->fn(ctx);
      } catch (const InputError& e) {
        throw InputError(fmt::format("{}: {}", config.file.source, e.what()));
      } catch (const RunFailure& e) {
        throw InputError(fmt::format("{}: {}: {}", config.file.source, entry->full_name(), e.what()));
      }
    }
  MemoryEstimate estimate;
  estimate.add("run", "process", "the executable, its libraries and thread stacks", process_base_bytes);
  for (MemoryStage stage : {MemoryStage::own, MemoryStage::derived})
    for (const auto* decl : config.decls)
      for (const auto& m : decl->memory)
        if (m.stage == stage) {
          Context ctx(state, *decl);
          try {
            m.fn(ctx, estimate);
          } catch (const InputError& e) {
            throw InputError(fmt::format("{}: {}", config.file.source, e.what()));
          }
        }
  const MemoryLimit limit = available_memory();
  if (estimate.total() > limit.bytes)
    throw InputError(fmt::format("{}: the run needs an estimated {}, more than the {} this process may use ({}); "
                                 "the largest parts: {}. Lower the parameters named there",
                                 config.file.source, format_bytes(estimate.total()), format_bytes(limit.bytes),
                                 limit.source, estimate.largest(3)));
  return estimate;
}

namespace {
// The command line goes into a YAML comment: a newline or other control character in it (a
// directory name can hold one) would end the comment and corrupt the file, so each is escaped.
std::string comment_safe(const std::string& text) {
  std::string out;
  for (unsigned char c : text) out += c < 0x20 || c == 0x7f ? fmt::format("\\x{:02x}", c) : std::string(1, static_cast<char>(c));
  return out;
}
}  // namespace

RunResult run(const Configuration& config, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // Cross-parameter checks before anything is written: bad input leaves no run directory.
  const MemoryEstimate memory = check_parameters(config);
  // So is a warm start that reads a run of another build or other parameters.
  WarmPoint warm;
  if (!options.warm_start.empty()) warm = find_warm_point(options.warm_start, config, build_description(config));
  const std::unique_ptr<RunDirectory> directory_owner =
      options.resume ? std::make_unique<RunDirectory>(options.run_directory, "run", RunDirectory::ReopenTag{})
                     : std::make_unique<RunDirectory>(options.run_directory, options.force, "run", options.protect);
  RunDirectory& directory = *directory_owner;
  RunState state(config);
  state.run_dir = options.run_directory;
  state.directory = &directory;
  const Provenance prov = provenance(options.command_line);
  state.provenance = {{"version", prov.version},   {"git_revision", prov.git_revision}, {"build_type", prov.build_type},
                      {"compiler", prov.compiler}, {"host", prov.host},                 {"date", prov.date},
                      {"command_line", prov.command_line}};
  const ParamSection& run_params = config.params.at("run");
#ifdef _OPENMP
  if (run_params.integer("threads") > 0) omp_set_num_threads(static_cast<int>(run_params.integer("threads")));
#endif
  const int checkpoint_every = static_cast<int>(run_params.integer("checkpoint_every"));
  const std::string build = options.resume || checkpoint_every > 0 ? build_description(config) : std::string();
  // A resume checks its checkpoint against this build and these parameters before it writes
  // anything: a refused one leaves the earlier run exactly as it was (warnings reach the terminal).
  ResumePoint resume;
  if (options.resume) resume = find_resume_point(state.run_dir, config, build, Log(&state.sink, ""));
  try {
    directory.record("log.txt.partial");
    directory.record("log.txt");
    state.sink.open_file(state.run_dir / "log.txt.partial", options.resume, state.run_dir / "log.txt");
    state.sink.set_verbose(options.verbose);
    directory.record("params.yaml");
    const bool kept = options.resume && require_own_entry(state.run_dir / "params.yaml", EntryKind::regular_file);
    std::ifstream earlier;
    if (kept) earlier.open(state.run_dir / "params.yaml", std::ios::binary);
    if (kept && earlier) {
      // The run's own record of its parameters (the checkpoint proved they match) stays as written.
      std::stringstream text;
      text << earlier.rdbuf();
      state.resolved_parameters = text.str();
    } else {
      state.resolved_parameters = resolved_parfile_yaml(config, fmt::format("# Resolved parameters of the run started by:\n#   {}\n"
                                                                            "# Run this file to reproduce it.\n",
                                                                            comment_safe(options.command_line)));
      write_file_atomic(state.run_dir / "params.yaml", state.resolved_parameters);
    }
  } catch (const InputError&) {
    // Nothing has run yet: leave no half-made run directory behind (a resumed one is left alone).
    if (!options.resume) {
      state.sink.abandon();
      directory.abandon();
    }
    throw;
  }
  if (options.resume) directory.take_over();
  const Log log(&state.sink, "");
  log.info("bhnsid {} ({}): {}", prov.version, prov.git_revision, comment_safe(options.command_line));
  log.info("run directory: {}", state.run_dir.string());
  log.info("memory: estimated {} (largest: {})", format_bytes(memory.total()), memory.largest(2));
  log.info("schedule:\n{}", format_schedule(config.schedule));
#ifdef _OPENMP
  log.info("OpenMP threads: {}", omp_get_max_threads());
#endif

  Executor exec(state);
  RunResult result;
  result.status = "completed";
  bool ok = true;
  // PARAMCHECK ran in check_parameters() above.
  for (Bin bin : {Bin::startup, Bin::setup, Bin::initial}) ok = ok && exec.run_bin(bin);
  const ContextOf context_of = [&exec](const std::string& plugin) -> Context& { return exec.context(plugin); };
  int first_iteration = 1;
  bool converged = false;
  if (ok && resume.file) {
    try {
      restore_checkpoint(state, context_of, *resume.file);
      first_iteration = resume.iteration + 1;
      converged = resume.converged;
      result.iterations = resume.iteration;
      log.info("resumed from {} after iteration {}{}", resume.file->path().string(), resume.iteration,
               converged ? " (converged: straight to ANALYSIS and OUTPUT)" : "");
    } catch (const std::exception& e) {
      exec.fail(fmt::format("--resume: {}", e.what()), exit_input);
      ok = false;
    }
    resume.file.reset();
  }
  if (ok && warm.file) {
    try {
      apply_warm_start(state, context_of, *warm.file);
      log.info("warm start from {} (iteration {}{}{}){}", warm.file->path().string(), warm.iteration,
               warm.converged ? ", converged" : ", not converged",
               warm.refined ? ", the next coarser lattice, interpolated" : "",
               warm.changed.empty() ? "" : fmt::format(": {}", warm.changed));
    } catch (const InputError& e) {  // a section its plugin cannot read
      exec.fail(fmt::format("--warm-start: {}", e.what()), exit_input);
      ok = false;
    } catch (const std::exception& e) {  // a plugin that could not rebuild its state from it
      exec.fail(fmt::format("--warm-start: {}", e.what()), exit_run_failed);
      ok = false;
    }
    warm.file.reset();
  }
  // A run whose restore failed holds the initial guess, not the earlier run's state: no OUTPUT over it.
  const bool reached_loop = ok;
  state.initial_data = ok;
  // A stop requested during the restore is polled here: a converged checkpoint has no loop to poll it.
  if (ok && exec.interrupted()) ok = false;
  bool checkpoint_write_failed = false;
  // The time the last checkpoint took and when it ended: a checkpoint waits until its cost is at
  // most run.checkpoint_overhead of the time since (at n = 128 one is 320 MB and 0.5 s, and an
  // iteration 1 s: every one would add 50 %).
  const double checkpoint_overhead = run_params.real("checkpoint_overhead");
  double checkpoint_cost = 0;
  auto checkpoint_end = std::chrono::steady_clock::now();
  if (ok && has_loop(config.schedule)) {
    const int max_iterations = static_cast<int>(run_params.integer("max_iterations"));
    // Retreating needs an UPDATE to undo (not before iteration 2) and someone to undo it.
    const int max_retreats = config.schedule.count(Bin::retreat) ? static_cast<int>(run_params.integer("max_retreats")) : 0;
    const bool has_checks = config.schedule.count(Bin::check) > 0;
    std::string detail;
    state.in_loop = true;
    directory.record("scalars.tsv");
    bool scalars_write_failed = false;
    for (int it = first_iteration; it <= max_iterations && ok && !converged; ++it) {
      const auto iteration_start = std::chrono::steady_clock::now();
      state.iteration = it;
      state.history.emplace_back();
      state.progress.clear();
      std::vector<std::string> waiting;
      const int retreats = solve_with_retreats(exec, log, state, it > 1 ? max_retreats : 0);
      ok = retreats >= 0 && exec.run_bin(Bin::update) && exec.run_checks(converged, detail, waiting);
      result.iterations = it;
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - iteration_start).count();
      state.history.back()["seconds"] = seconds;
      if (std::find(state.history_columns.begin(), state.history_columns.end(), "seconds") == state.history_columns.end())
        state.history_columns.push_back("seconds");
      if (ok) {
        // The terminal gets one line per iteration, the log every check's detail as well.
        std::string line = fmt::format("iteration {}/{}:", it, max_iterations);
        for (const auto& [name, value] : state.progress) line += fmt::format(" {} {:.9g}", name, value);
        if (retreats > 0) line += fmt::format(", {} retreat(s)", retreats);
        line += fmt::format(", {:.2f} s", seconds);
        if (has_checks) line += converged ? ", converged" : fmt::format(", waiting for {}", fmt::join(waiting, ", "));
        log.info(line);
        log.detail("iteration {} checks: {}", it, has_checks ? detail : "no CHECK entries, one pass");
      }
      // Rewritten every iteration, so that a long run's progress is on disk (and survives a kill); a
      // failed write (a full disk) is said once and retried at the end, where it is an error.
      try {
        write_file_atomic(state.run_dir / "scalars.tsv", scalars_tsv(state));
      } catch (const InputError& e) {
        if (!scalars_write_failed) log.warn("scalars.tsv not updated during the loop: {}", e.what());
        scalars_write_failed = true;
      }
      const double since_checkpoint =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - checkpoint_end).count();
      const bool last = converged || !has_checks;
      if (ok && checkpoint_every > 0 &&
          (last || (it % checkpoint_every == 0 && checkpoint_cost <= checkpoint_overhead * since_checkpoint))) {
        const auto checkpoint_start = std::chrono::steady_clock::now();
        // Like scalars.tsv, a checkpoint the disk refuses is said once and does not stop the run.
        try {
          save_checkpoint(state, context_of, converged, build);
          checkpoint_end = std::chrono::steady_clock::now();
          checkpoint_cost = std::chrono::duration<double>(checkpoint_end - checkpoint_start).count();
          log.detail("iteration {}: checkpoint written in {:.3f} s", it, checkpoint_cost);
        } catch (const InputError& e) {
          if (!checkpoint_write_failed) log.warn("checkpoint not written: {}", e.what());
          checkpoint_write_failed = true;
        } catch (const std::exception& e) {
          exec.fail(fmt::format("writing the checkpoint of iteration {}: internal error: {}", it, e.what()), exit_internal);
          ok = false;
        }
      }
      if (!has_checks) break;
    }
    state.in_loop = false;
    if (ok && has_checks) {
      if (converged)
        result.status = "converged";
      else
        exec.fail(fmt::format("the loop did not converge in run.max_iterations = {} iterations: {}", max_iterations,
                              detail),
                  exit_run_failed);
    }
    ok = ok && (converged || !has_checks);
  }
  // Diagnostics of an unconverged state would mislead, so ANALYSIS needs success; OUTPUT keeps the
  // last state of any run that got as far as the loop, interrupted or not; TERMINATE always runs.
  // None of these three stops for a signal: they are what makes an interrupted run worth keeping.
  if (ok) ok = exec.run_bin(Bin::analysis, false);
  // A resume interrupted before its restore holds the initial guess: the earlier run's output stays.
  if (reached_loop || (exec.signal() != 0 && !options.resume)) exec.run_bin(Bin::output, false);
  exec.run_bin(Bin::terminate, false);

  std::string message = exec.failure();
  result.exit_code = message.empty() ? exit_ok : exec.failure_code();
  if (result.exit_code != exit_ok) result.status = "failed";
  if (exec.signal() != 0 && message.empty()) {
    result.status = "interrupted";
    result.exit_code = 128 + exec.signal();
    message = fmt::format("interrupted by {} at iteration {}; the fields are the last state reached", signal_name(exec.signal()),
                          state.iteration);
  }
  result.memory_estimate = memory.total();
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  log.info("status: {} after {} iteration(s), {:.3f} s", result.status, result.iterations, total);
  const auto write = [&](const std::string& name, const std::string& text) {
    directory.record(name);
    write_file_atomic(state.run_dir / name, text);
  };
  write("timers.tsv", timers_tsv(exec.timers(), total));
  if (!state.history.empty()) write("scalars.tsv", scalars_tsv(state));
  write("summary.json", summary_json(state, result, message, prov));
  state.sink.finish(state.run_dir / "log.txt");
  return result;
}

}  // namespace bhnsid::core
