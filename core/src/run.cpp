#include "bhnsid/core/run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "bhnsid/core/atomic_file.hpp"
#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
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

  bool run_bin(Bin bin) {
    auto it = state_.config.schedule.find(bin);
    if (it == state_.config.schedule.end()) return true;
    for (const auto* entry : it->second) {
      if (!call(*entry, [&](Context& ctx) { entry->fn(ctx); })) return false;
    }
    return true;
  }

  /// Returns false when a CHECK entry failed outright; `all_converged` and `detail` report the rest.
  bool run_checks(bool& all_converged, std::string& detail) {
    all_converged = true;
    detail.clear();
    auto it = state_.config.schedule.find(Bin::check);
    if (it == state_.config.schedule.end()) return true;
    for (const auto* entry : it->second) {
      Convergence result;
      if (!call(*entry, [&](Context& ctx) { result = entry->check(ctx); })) return false;
      all_converged = all_converged && result.converged;
      detail += fmt::format("{}{}: {}{}", detail.empty() ? "" : "; ", entry->full_name(),
                            result.converged ? "converged" : "not converged",
                            result.detail.empty() ? "" : " (" + result.detail + ")");
    }
    return true;
  }

  const std::vector<Timer>& timers() const { return timers_; }
  const std::string& failure() const { return failure_; }
  int failure_code() const { return failure_code_; }
  void fail(const std::string& message, int code) {
    if (failure_.empty()) {
      failure_ = message;
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
    try {
      body(contexts_.at(entry.plugin));
    } catch (const RunFailure& e) {
      fail(fmt::format("{}: {}", entry.full_name(), e.what()), exit_run_failed);
      ok = false;
    } catch (const InputError& e) {
      fail(fmt::format("{}: {}", entry.full_name(), e.what()), exit_input);
      ok = false;
    } catch (const std::exception& e) {
      fail(fmt::format("{}: internal error: {}", entry.full_name(), e.what()), exit_internal);
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
  std::string failure_;
  int failure_code_ = 0;
};

bool has_loop(const Schedule& schedule) {
  return schedule.count(Bin::solve) || schedule.count(Bin::update) || schedule.count(Bin::check);
}

std::string timers_tsv(const std::vector<Timer>& timers, double total) {
  std::string out = "bin\tentry\tcalls\tseconds\n";
  for (const auto& t : timers) out += fmt::format("{}\t{}\t{}\t{:.6f}\n", t.bin, t.entry, t.calls, t.seconds);
  return out + fmt::format("TOTAL\ttotal\t1\t{:.6f}\n", total);
}

std::string history_tsv(const RunState& state) {
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
  return j.dump(2) + "\n";
}

}  // namespace

void check_parameters(const Configuration& config) {
  auto it = config.schedule.find(Bin::paramcheck);
  if (it == config.schedule.end()) return;
  RunState state(config);
  for (const auto* entry : it->second) {
    const PluginDecl* decl = nullptr;
    for (const auto* d : config.decls)
      if (d->name == entry->plugin) decl = d;
    Context ctx(state, *decl);
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
}

RunResult run(const Configuration& config, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // Cross-parameter checks before anything is written: bad input leaves no run directory.
  check_parameters(config);
  prepare_run_directory(options.run_directory, options.force);
  RunState state(config);
  state.run_dir = options.run_directory;
  const Provenance prov = provenance(options.command_line);
  try {
    state.sink.open_file(state.run_dir / "log.txt.partial");
    write_file_atomic(state.run_dir / "params.yaml",
                      resolved_parfile_yaml(config, fmt::format("# Resolved parameters of the run started by:\n#   {}\n"
                                                                "# Run this file to reproduce it.\n",
                                                                options.command_line)));
  } catch (const InputError&) {
    // Nothing has run yet: leave no half-made run directory behind.
    std::error_code ec;
    std::filesystem::remove_all(state.run_dir, ec);
    throw;
  }
  const Log log(&state.sink, "");
  log.info("bhnsid {} ({}): {}", prov.version, prov.git_revision, options.command_line);
  log.info("run directory: {}", state.run_dir.string());
  log.info("schedule:\n{}", format_schedule(config.schedule));
  const ParamSection& run_params = config.params.at("run");
#ifdef _OPENMP
  if (run_params.integer("threads") > 0) omp_set_num_threads(static_cast<int>(run_params.integer("threads")));
  log.info("OpenMP threads: {}", omp_get_max_threads());
#endif

  Executor exec(state);
  RunResult result;
  result.status = "completed";
  bool ok = true;
  // PARAMCHECK ran in check_parameters() above.
  for (Bin bin : {Bin::startup, Bin::setup, Bin::initial}) ok = ok && exec.run_bin(bin);
  const bool reached_loop = ok;
  if (ok && has_loop(config.schedule)) {
    const int max_iterations = static_cast<int>(run_params.integer("max_iterations"));
    const bool has_checks = config.schedule.count(Bin::check) > 0;
    bool converged = false;
    std::string detail;
    state.in_loop = true;
    for (int it = 1; it <= max_iterations && ok && !converged; ++it) {
      state.iteration = it;
      state.history.emplace_back();
      ok = exec.run_bin(Bin::solve) && exec.run_bin(Bin::update) && exec.run_checks(converged, detail);
      result.iterations = it;
      if (ok) log.info("iteration {}/{}: {}", it, max_iterations, has_checks ? detail : "no CHECK entries, one pass");
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
  // last state of any run that got as far as the loop; TERMINATE always runs.
  if (ok) ok = exec.run_bin(Bin::analysis);
  if (reached_loop) exec.run_bin(Bin::output);
  exec.run_bin(Bin::terminate);

  result.exit_code = exec.failure().empty() ? exit_ok : exec.failure_code();
  if (result.exit_code != exit_ok) result.status = "failed";
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  log.info("status: {} after {} iteration(s), {:.3f} s", result.status, result.iterations, total);
  write_file_atomic(state.run_dir / "timers.tsv", timers_tsv(exec.timers(), total));
  if (!state.history.empty()) write_file_atomic(state.run_dir / "history.tsv", history_tsv(state));
  write_file_atomic(state.run_dir / "summary.json", summary_json(state, result, exec.failure(), prov));
  state.sink.finish(state.run_dir / "log.txt");
  return result;
}

}  // namespace bhnsid::core
