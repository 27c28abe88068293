// bhnsid validate: the configuration at dx, dx/2, dx/4 on the same cube, an independent residual
// evaluator on each, and the convergence order of every equation's residual. It knows no plugin:
// the parameters that follow the resolution are those the plugins declare (ParamHandle::refines),
// and the equations and their norms are what the evaluator reports (core/residual_report.hpp).
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <signal.h>
#include <sstream>

#include "bhnsid/core/atomic_file.hpp"
#include "bhnsid/core/configuration.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/residual_report.hpp"
#include "bhnsid/core/interrupt.hpp"
#include "bhnsid/core/owned_entry.hpp"
#include "bhnsid/core/run.hpp"
#include "bhnsid/core/run_directory.hpp"
#include "commands.hpp"

extern char** environ;

namespace bhnsid::cli {

using namespace bhnsid::core;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

struct Level {
  std::map<std::string, std::string> refined;  // the refined parameters' values, as --set text
  fs::path dir;
  double seconds = 0;
  std::map<std::string, double> scalars;
  std::vector<std::vector<double>> axis;  // rows of residual_axis.tsv (x, then the residual columns)
  std::vector<std::string> axis_names;
  std::vector<std::string> regions;  // per axis row: away, surface, puncture or -
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw RunFailure(fmt::format("validate: cannot read {}", p.string()));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs argv, never through a shell (a directory's name is an argument, whatever it holds), with
// stdout and stderr into `log` (created afresh: never through a link left there), or the terminal's
// when `log` is empty; returns the exit status.
int spawn(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int log_fd = log.empty() ? -1 : create_fresh_file(log);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (log_fd >= 0) {
    posix_spawn_file_actions_adddup2(&actions, log_fd, 1);
    posix_spawn_file_actions_adddup2(&actions, log_fd, 2);
  }
  // The level runs in a process group of its own: a terminal's Ctrl-C reaches validate alone, which
  // passes each stopping signal on exactly once (interrupt.cpp), so that the first stops the level
  // at its safe point and only a second ends it at once.
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t stopping, none, before;
  sigemptyset(&stopping);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&stopping, sig);
  sigemptyset(&none);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setsigmask(&attr, &none);
  // Held back until the child is known to the handler, then delivered (and passed on) at once.
  sigprocmask(SIG_BLOCK, &stopping, &before);
  pid_t pid = 0;
  const int rc = interrupt_signal() != 0 ? -1 : posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
  if (rc == 0) forward_interrupts_to(pid);
  sigprocmask(SIG_SETMASK, &before, nullptr);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (log_fd >= 0) ::close(log_fd);
  if (rc < 0)
    throw Interrupted(fmt::format("validate: interrupted by {} before {} started", signal_name(interrupt_signal()), args[1]));
  if (rc != 0) throw RunFailure(fmt::format("validate: cannot start {}: {}", args[0], std::strerror(rc)));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) {
      forward_interrupts_to(0);
      throw RunFailure(fmt::format("validate: waiting for {}: {}", args[0], std::strerror(errno)));
    }
  forward_interrupts_to(0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Progress and the table go to the terminal best effort: a closed pipe must not end the series,
// whose results are in validate.json.
template <class... Args>
void say(fmt::format_string<Args...> format, Args&&... args) {
  const std::string text = fmt::format(format, std::forward<Args>(args)...);
  std::fwrite(text.data(), 1, text.size(), stdout);
  std::fflush(stdout);
}

void read_axis(Level& lv) {
  std::istringstream in(read_text(lv.dir / residual_report::axis_file));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::istringstream row(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(row, cell, '\t')) cells.push_back(cell);
    if (line[0] == '#') {
      cells[0] = "x";  // "# x"
      lv.axis_names.assign(cells.begin(), cells.end() - 1);  // the last column is the region
      continue;
    }
    std::vector<double> values;
    for (std::size_t c = 0; c + 1 < cells.size(); ++c) values.push_back(cells[c] == "nan" ? std::nan("") : std::stod(cells[c]));
    lv.axis.push_back(values);
    lv.regions.push_back(cells.back());
  }
}

/// A parameter that follows the resolution, and its value at level q as --set text.
struct Refined {
  std::string key;  // section.name
  const ParamSpec* spec = nullptr;
  ParamValue base;

  std::string at(int q) const {
    const bool doubles = spec->refinement == Refinement::doubles;
    if (spec->type == ParamType::integer) {
      const std::int64_t v = std::get<std::int64_t>(base);
      if (doubles) {
        if (v < 0 || v > (std::numeric_limits<std::int64_t>::max() >> q))
          throw InputError(fmt::format("validate: {} = {} cannot be doubled {} times", key, v, q));
        return fmt::format("{}", v << q);
      }
      if (v % (std::int64_t{1} << q) != 0)
        throw InputError(fmt::format("validate: {} = {} cannot be halved {} times exactly", key, v, q));
      return fmt::format("{}", v >> q);
    }
    const double v = std::get<double>(base);
    return fmt::format("{:.17g}", doubles ? std::ldexp(v, q) : std::ldexp(v, -q));
  }
};

std::vector<Refined> refined_parameters(const Configuration& config, const std::string& parfile) {
  std::vector<Refined> out;
  bool spacing = false;
  for (const PluginDecl* decl : config.decls)
    for (const ParamSpec& spec : decl->params) {
      if (spec.refinement == Refinement::none) continue;
      out.push_back({decl->name + "." + spec.name, &spec, config.params.at(decl->name).values().at(spec.name)});
      spacing = spacing || spec.refinement == Refinement::halves;
    }
  if (!spacing)
    throw InputError(fmt::format("{}: validate needs a parameter that halves with the resolution (a grid spacing); no "
                                 "plugin in plugins declares one",
                                 parfile));
  return out;
}

bool is_refined(const std::vector<Refined>& refined, const std::string& override_text) {
  const std::string key = override_text.substr(0, override_text.find('='));
  return std::any_of(refined.begin(), refined.end(), [&](const Refined& r) { return r.key == key; });
}

std::string describe(const Level& lv) {
  std::string out;
  for (const auto& [key, value] : lv.refined) out += (out.empty() ? "" : ", ") + key + " = " + value;
  return out;
}

double order(double coarse, double fine) { return coarse > 0 && fine > 0 ? std::log2(coarse / fine) : std::nan(""); }

/// The equations the evaluator reports (a residual_E_judged scalar each), by name; --only must name
/// judged ones.
std::vector<std::string> reported_equations(const Level& lv, const std::vector<std::string>& only) {
  std::vector<std::string> equations;
  const std::string judged_suffix = "_judged";
  const std::size_t prefix = std::strlen(residual_report::prefix);
  for (const auto& [key, value] : lv.scalars)
    if (key.rfind(residual_report::prefix, 0) == 0 && key.size() > prefix + judged_suffix.size() &&
        key.compare(key.size() - judged_suffix.size(), judged_suffix.size(), judged_suffix) == 0)
      equations.push_back(key.substr(prefix, key.size() - prefix - judged_suffix.size()));
  if (equations.empty())
    throw RunFailure(fmt::format("validate: the run at {} reports no residual (no {}E{} scalar in {})", describe(lv),
                                 residual_report::prefix, judged_suffix, (lv.dir / "summary.json").string()));
  for (const std::string& e : only)
    if (std::find(equations.begin(), equations.end(), e) == equations.end() ||
        lv.scalars.at(residual_report::key(e, "judged")) == 0)
      throw InputError(fmt::format("validate: --only {}: expected one of the equations the evaluator judges ({})", e,
                                   fmt::join(equations, ", ")));
  return equations;
}

}  // namespace

int cmd_validate(const std::string& parfile, const CommonOptions& common, const ValidateOptions& opt) {
  if (opt.levels < 2) throw InputError(fmt::format("validate: --levels {}: expected at least 2", opt.levels));
  if (!(opt.threshold > 0)) throw InputError(fmt::format("validate: --threshold {}: expected a positive order", opt.threshold));
  // Each level doubles n: bounded so that n << (levels - 1) cannot overflow, and far beyond what
  // any machine holds (the finest level is checked below, memory included, before any run).
  if (opt.levels > max_validate_levels)
    throw InputError(fmt::format("validate: --levels {}: expected at most {} (each level has 8 times the points of the "
                                 "one before)",
                                 opt.levels, max_validate_levels));
  PluginLoader loader(plugin_search_path(common.plugin_dirs));
  // The file is read once (regular files only), with the --with plugins added; input errors, their
  // parameters' included, surface here before any run.
  ParFile file = load_parfile(parfile);
  for (const std::string& name : opt.with)
    if (std::find(file.plugins.begin(), file.plugins.end(), name) == file.plugins.end()) {
      file.plugins.push_back(name);
      file.plugin_pos.push_back(TextPos{parfile, 0, 0});
    }
  const Configuration config = configure(file, common.overrides, loader);
  check_parameters(config);
  bool evaluator = false;
  for (const PluginDecl* decl : config.decls)
    for (const std::string& cap : decl->implements) evaluator = evaluator || cap == residual_report::capability;
  if (!evaluator)
    throw InputError(fmt::format("{}: validate needs an independent residual evaluator, a plugin that implements '{}': "
                                 "list it in plugins or name it with --with",
                                 parfile, residual_report::capability));
  const std::vector<Refined> refined = refined_parameters(config, parfile);
  // Every level's values now, so that one that cannot be formed is an input error before any run.
  for (int q = 0; q < opt.levels; ++q)
    for (const Refined& r : refined) (void)r.at(q);
  const fs::path dir = opt.output.empty() ? fs::path("runs") / (fs::path(parfile).stem().string() + "_validate") : fs::path(opt.output);
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const auto level_args = [&](int q, const std::string& command, const fs::path& parfile_copy) {
    // Every refined parameter follows the spacing: the grid's points, and the excluded regions,
    // which keep their size in length, not in points, as dx shrinks.
    std::vector<std::string> args{self, command, parfile_copy.string()};
    for (const Refined& r : refined) args.insert(args.end(), {"--set", r.key + "=" + r.at(q)});
    for (const std::string& o : common.overrides)
      if (!is_refined(refined, o)) args.insert(args.end(), {"--set", o});
    for (const std::string& p : common.plugin_dirs) args.insert(args.end(), {"--plugin-path", p});
    return args;
  };

  RunDirectory directory(dir, opt.force, "validate", {fs::path(parfile)});
  directory.record("parfile.yaml");
  write_file_atomic(dir / "parfile.yaml",
                    resolved_parfile_yaml(config, "# The parameter file of bhnsid validate (--with plugins added), resolved\n"));
  // The finest level is the largest: if it cannot run (grid.n beyond its range, memory), say so now,
  // in its own words, not after the coarser levels have run.
  {
    directory.record("finest_check.out");
    const fs::path out = dir / "finest_check.out";
    const int rc = spawn(level_args(opt.levels - 1, "check", dir / "parfile.yaml"), out);
    if (interrupt_signal() != 0)
      throw Interrupted(fmt::format("validate: interrupted by {} while checking the finest level", signal_name(interrupt_signal())));
    if (rc != 0) {
      std::string why = read_text(out);
      while (!why.empty() && why.back() == '\n') why.pop_back();
      const std::string prefix = "bhnsid: error: ";
      if (why.rfind(prefix, 0) == 0) why = why.substr(prefix.size());
      directory.abandon();  // bad input leaves no directory behind
      Level finest;
      for (const Refined& r : refined) finest.refined[r.key] = r.at(opt.levels - 1);
      throw InputError(fmt::format("validate: the finest level ({}) cannot run: {}", describe(finest), why));
    }
  }

  std::vector<Level> levels(static_cast<std::size_t>(opt.levels));
  std::vector<std::string> equations;
  for (int q = 0; q < opt.levels; ++q) {
    Level& lv = levels[static_cast<std::size_t>(q)];
    for (const Refined& r : refined) lv.refined[r.key] = r.at(q);
    lv.dir = dir / fmt::format("level_{}", q);
    std::vector<std::string> args = level_args(q, "run", dir / "parfile.yaml");
    args.insert(args.begin() + 3, {"--output", lv.dir.string()});
    directory.record(fmt::format("level_{}", q));
    directory.record(fmt::format("level_{}.out", q));
    say("validate: level {} of {}: {} ...\n", q + 1, opt.levels, describe(lv));
    const auto t0 = std::chrono::steady_clock::now();
    const int rc = spawn(args, dir / fmt::format("level_{}.out", q));
    lv.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (interrupt_signal() != 0)
      throw Interrupted(fmt::format("validate: interrupted by {} during the run at {}; its state is in {}",
                                    signal_name(interrupt_signal()), describe(lv), lv.dir.string()));
    if (rc != 0)
      throw RunFailure(fmt::format("validate: the run at {} failed (exit {}); see {} and {}", describe(lv), rc,
                                   (dir / fmt::format("level_{}.out", q)).string(), (lv.dir / "log.txt").string()));
    const json summary = json::parse(read_text(lv.dir / "summary.json"));
    for (const auto& [key, value] : summary["scalars"].items())
      if (value.is_number()) lv.scalars[key] = value.get<double>();
    read_axis(lv);
    say("validate:   done in {:.1f} s\n", lv.seconds);
    if (q == 0) {
      try {
        equations = reported_equations(lv, opt.only);
      } catch (const InputError&) {
        directory.abandon();  // bad input (--only) leaves no directory behind
        throw;
      }
    }
  }

  json out;
  out["parfile"] = parfile;
  out["threshold"] = opt.threshold;
  for (const Level& lv : levels) out["levels"].push_back({{"parameters", lv.refined}, {"run_directory", lv.dir.string()}, {"seconds", lv.seconds}});
  bool passed = true;
  say("\n{:<12} {:>10} {:>10} {:>10} {:>8} {:>8} {:>8}  {}\n", "equation", "L2 (dx)", "L2 (dx/2)", "L2 (dx/4)",
             "order", "order", "max ord", "verdict");
  for (const std::string& e : equations) {
    using residual_report::key;
    if (!levels[0].scalars.count(key(e, "l2"))) continue;
    json eq;
    std::vector<double> l2, mx, sl2;
    for (const Level& lv : levels) {
      if (!lv.scalars.count(key(e, "l2")) || !lv.scalars.count(key(e, "max")))
        throw RunFailure(fmt::format("validate: the run at {} does not report {}", describe(lv), key(e, "l2")));
      l2.push_back(lv.scalars.at(key(e, "l2")));
      mx.push_back(lv.scalars.at(key(e, "max")));
      if (lv.scalars.count(key(e, "surface_l2"))) sl2.push_back(lv.scalars.at(key(e, "surface_l2")));
    }
    std::vector<double> o2, omax, osurf;
    for (std::size_t q = 0; q + 1 < l2.size(); ++q) {
      o2.push_back(order(l2[q], l2[q + 1]));
      omax.push_back(order(mx[q], mx[q + 1]));
      if (q + 1 < sl2.size()) osurf.push_back(order(sl2[q], sl2[q + 1]));
    }
    std::string verdict;
    bool exact = true;
    for (double v : l2) exact = exact && v <= 1e-12;
    const bool judged = opt.only.empty() || std::find(opt.only.begin(), opt.only.end(), e) != opt.only.end();
    if (exact) {
      verdict = "exact (zero at every level)";
    } else if (!judged) {
      verdict = "reported (not in --only)";
    } else if (levels[0].scalars.at(key(e, "judged")) == 0) {
      verdict = "reported (the evaluator does not expect it to converge)";
    } else if (o2.back() >= opt.threshold) {
      verdict = "pass";
    } else {
      verdict = fmt::format("FAIL (order {:.2f} < {:.2f})", o2.back(), opt.threshold);
      passed = false;
    }
    eq["l2"] = l2;
    eq["max"] = mx;
    eq["order_l2"] = o2;
    eq["order_max"] = omax;
    if (!sl2.empty()) {
      eq["surface_l2"] = sl2;
      eq["surface_order_l2"] = osurf;
    }
    eq["verdict"] = verdict;
    out["equations"][e] = eq;
    std::string l2s;
    for (std::size_t q = 0; q < 3; ++q) l2s += q < l2.size() ? fmt::format(" {:>10.3e}", l2[q]) : fmt::format(" {:>10}", "");
    say("{:<12}{} {:>8.2f} {:>8.2f} {:>8.2f}  {}\n", e, l2s, o2.front(), o2.back(), omax.back(), verdict);
    if (!sl2.empty() && !exact)
      say("{:<12} surface band: L2 {:.3e} -> {:.3e}, order {:.2f}\n", "", sl2.front(), sl2.back(), osurf.back());
  }
  // Pointwise: the residuals at the coarsest run's axis points (every run evaluates there),
  // times 4^q at level q.
  const Level& coarse = levels[0];
  for (const Level& lv : levels) {
    bool same = lv.axis.size() == coarse.axis.size();
    for (std::size_t i = 0; same && i < coarse.axis.size(); ++i) same = std::fabs(lv.axis[i][0] - coarse.axis[i][0]) <= 1e-9 * (1 + std::fabs(coarse.axis[i][0]));
    if (!same) throw RunFailure(fmt::format("validate: the x-axis points of {} differ from the coarsest run's", (lv.dir / residual_report::axis_file).string()));
  }
  json axis;
  for (std::size_t c = 0; c < coarse.axis_names.size(); ++c) {
    std::vector<std::vector<double>> series;
    for (std::size_t q = 0; q < levels.size(); ++q) {
      std::vector<double> values;
      for (std::size_t i = 0; i < coarse.axis.size(); ++i) {
        const std::vector<double>& row = levels[q].axis[i];
        values.push_back(c == 0 ? row[c] : row[c] * std::pow(4.0, static_cast<double>(q)));
      }
      series.push_back(values);
    }
    axis[coarse.axis_names[c]] = c == 0 ? json(series[0]) : json(series);
  }
  out["axis_rescaled"] = axis;
  out["axis_region"] = coarse.regions;
  out["passed"] = passed;
  directory.record("validate.json");
  write_file_atomic(dir / "validate.json", out.dump(1, ' ', false, json::error_handler_t::replace) + "\n");
  say("\nvalidate: {} ({} levels, threshold {:.2f}); validate.json in {}\n", passed ? "PASSED" : "FAILED",
             opt.levels, opt.threshold, dir.string());
  if (opt.plots) {
    // Debian's interpreter, where matplotlib is installed (scripts/install-deps.sh), before any other on PATH.
    const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    // Installed beside the executable (PREFIX/share/bhnsid), else in the source tree it was built from.
    std::error_code ec;
    const fs::path installed = fs::read_symlink("/proc/self/exe", ec).parent_path().parent_path() / "share" / "bhnsid" /
                               "plot_validate.py";
    const std::string script = !ec && fs::exists(installed) ? installed.string() : std::string(BHNSID_PLOT_SCRIPT);
    std::set<std::string> before;
    for (const auto& e : fs::directory_iterator(dir)) before.insert(e.path().filename().string());
    const int rc = spawn({python, script, (dir / "validate.json").string(), dir.string()}, {});
    // What the plot script wrote is ours, so that --force may replace it.
    for (const auto& e : fs::directory_iterator(dir))
      if (!before.count(e.path().filename().string())) directory.record(e.path().filename().string());
    if (interrupt_signal() != 0)
      throw Interrupted(fmt::format("validate: interrupted by {} while plotting; the table and validate.json are "
                                    "complete in {}",
                                    signal_name(interrupt_signal()), dir.string()));
    if (rc != 0)
      std::fprintf(stderr, "validate: warning: the plots were not made (%s exited with status %d); the table and "
                   "validate.json are complete\n", script.c_str(), rc);
  }
  return passed ? exit_ok : exit_run_failed;
}

}  // namespace bhnsid::cli
