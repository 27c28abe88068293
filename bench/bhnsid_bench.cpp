// bhnsid-bench: performance of the production path, printed as one JSON line per case.
//
//   bhnsid-bench poisson --n N [--threads T] [--reps R]
//   bhnsid-bench puncture --n N [--threads T] [--reps R]
//   bhnsid-bench binary --n N [--threads T] [--reps R] [--parfile FILE]
//   bhnsid-bench sweep [--n N] [--threads T] [--lower none|momentum|shift|shift-no-hole]
//   bhnsid-bench robin [--n N] [--threads T]
//   bhnsid-bench colour-split [--n N] [--threads T]
//   bhnsid-bench boxes [--n N] [--boxes B] [--threads T] [--reps R]
//
// solves the hypre peer's problem (../shared/peers/src/problem.hpp: -Laplace u = f on the unit
// cube, N^3 interior unknowns, h = 1/(N+1), homogeneous Dirichlet, u = g(x)g(y)g(z) with
// g(t) = t(1-t)e^t) through the real plugins (grid, multigrid, mms) exactly as `bhnsid run` does,
// to discretization error, and reports the best of R warm runs, setup included (plugin
// configuration, allocation, source terms, solve, analysis).
#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bhnsid/core/configuration.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/parfile.hpp"
#include "bhnsid/core/run.hpp"
#include "bhnsid/core/yaml_tree.hpp"
#include "colour_split.hpp"
#include "robin.hpp"
#include "sweep.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The run's own log goes to the terminal; the benchmark's only output is its JSON line.
class Silence {
 public:
  Silence() {
    std::fflush(stdout);
    std::fflush(stderr);
    saved_out_ = dup(1);
    saved_err_ = dup(2);
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    close(null);
  }
  ~Silence() {
    std::fflush(stdout);
    std::fflush(stderr);
    dup2(saved_out_, 1);
    dup2(saved_err_, 2);
    close(saved_out_);
    close(saved_err_);
  }

 private:
  int saved_out_, saved_err_;
};

struct Measured {
  double seconds;
  json summary;
  double cycle_seconds = 0;  ///< mean of the cycles after the FMG start (each with its residual check)
};

// The mean time of the V-cycles on the finest level after the FMG start, from the run's
// multigrid_history.tsv (cycle, seconds, ...): what one cycle of the equations costs, apart from
// how many cycles they need and from set-up.
double mean_cycle_seconds(const fs::path& history) {
  std::ifstream in(history);
  std::string line;
  double sum = 0;
  int count = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    int cycle = 0;
    double seconds = 0;
    if (!(row >> cycle >> seconds)) throw std::runtime_error("unreadable line in " + history.string() + ": " + line);
    if (cycle >= 1) sum += seconds, ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

Measured run_once(const std::string& parfile_text, const std::vector<std::string>& overrides,
                  const fs::path& directory) {
  using namespace bhnsid::core;
  PluginLoader loader(plugin_search_path({}));
  ParFile file = parse_parfile(parse_yaml(parfile_text, "bhnsid-bench.yaml"));
  RunResult result;
  const auto start = std::chrono::steady_clock::now();
  {
    Silence quiet;
    Configuration config = configure(std::move(file), overrides, loader);
    RunOptions options;
    options.run_directory = directory;
    options.force = true;
    options.command_line = "bhnsid-bench";
    result = run(config, options);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ifstream in(directory / "summary.json");
  json summary = json::parse(in);
  if (result.exit_code != 0)
    throw std::runtime_error("the benchmark run failed (status " + result.status + "); see " +
                             (directory / "log.txt").string());
  return {seconds, summary, mean_cycle_seconds(directory / "multigrid_history.tsv")};
}

Measured best_of(const std::string& parfile_text, const std::vector<std::string>& overrides, int reps) {
  const fs::path directory = fs::temp_directory_path() / ("bhnsid-bench-" + std::to_string(getpid()));
  Measured best{1e300, {}};
  for (int r = 0; r <= reps; ++r) {  // run 0 warms up (page cache, plugin loading)
    Measured m = run_once(parfile_text, overrides, directory);
    if (r > 0 && m.seconds < best.seconds) best = m;
  }
  fs::remove_all(directory);
  return best;
}

// The Poisson benchmark's cycle, V(2,2) with omega = 1.2 (see main).
const std::vector<std::string> poisson_cycle{"multigrid.pre_sweeps=2", "multigrid.post_sweeps=2", "multigrid.omega=1.2"};

std::string poisson_parfile(int n, int threads, double tau_factor) {
  std::ostringstream par;
  par << "plugins: [grid, multigrid, mms]\n"
      << "run:\n  threads: " << threads << "\n"
      << "grid:\n  n: " << n + 1 << "\n  dx: " << 1.0 / (n + 1) << "\n  symmetry: none\n"
      << "multigrid:\n  tau_factor: " << tau_factor << "\n"
      << "mms:\n  problem: poisson\n";
  return par.str();
}

// The eight field equations of a single boosted puncture (parfiles/boosted_puncture.yaml: r_c = 20 M,
// P_y = 0.3, equatorial symmetry) at n intervals, beside the Poisson benchmark at the same n (its
// N = n - 1 interior points per axis, no symmetry), both solved with the solver's defaults to
// |r| <= 1e-3 |tau| in one process: the measure of what the physics costs over Poisson.
// "ratio" and "median_pair_ratio" compare whole runs (as the Poisson benchmark times them);
// "solve_ratio" and "median_pair_solve_ratio" the multigrid cycles alone (FMG and cycles);
// "median_pair_cycle_ratio" one finest-level cycle after the FMG start.
int puncture(int n, int threads, int reps, double tau_factor) {
  if (n < 8 || (n & (n - 1)) != 0) {
    std::cerr << "bhnsid-bench puncture: --n must be a power of 2 (intervals), got " << n << "\n";
    return 2;
  }
  std::ostringstream par;
  par << "plugins: [grid, multigrid, puncture, hamiltonian, lapse, momentum, shift, diagnostics]\n"
      << "run:\n  threads: " << threads << "\n"
      << "grid:\n  n: " << n << "\n  dx: " << 40.0 / n << "\n"
      << "multigrid:\n  tau_factor: " << tau_factor << "\n"
      << "puncture:\n  bare_mass: 1.0\n  position: [0.1, 0.0, 0.0]\n  momentum: [0.0, 0.3, 0.0]\n";
  // The two runs alternate (after one warm-up each), so that both see the same state of a machine
  // whose speed drifts; each pair's ratio is kept, and their median reported beside the ratio of
  // the best times.
  const std::string poisson_par = poisson_parfile(n - 1, threads, tau_factor);
  const fs::path directory = fs::temp_directory_path() / ("bhnsid-bench-" + std::to_string(getpid()));
  Measured eight{1e300, {}}, poisson{1e300, {}};
  std::vector<double> pair_ratios, pair_solve_ratios, pair_cycle_ratios;
  auto solve_seconds = [](const Measured& m) { return m.summary["scalars"].value("multigrid_seconds", 0.0); };
  for (int r = 0; r <= reps; ++r) {
    const Measured a = run_once(par.str(), {}, directory), b = run_once(poisson_par, {}, directory);
    if (r == 0) continue;
    if (a.seconds < eight.seconds) eight = a;
    if (b.seconds < poisson.seconds) poisson = b;
    pair_ratios.push_back(a.seconds / b.seconds);
    pair_solve_ratios.push_back(solve_seconds(a) / std::max(1e-300, solve_seconds(b)));
    if (a.cycle_seconds > 0 && b.cycle_seconds > 0) pair_cycle_ratios.push_back(a.cycle_seconds / b.cycle_seconds);
  }
  fs::remove_all(directory);
  auto median_of = [](std::vector<double> v) {
    if (v.empty()) return 0.0;  // no cycle after the FMG start in a run: nothing to compare
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size();
    return m % 2 ? v[m / 2] : 0.5 * (v[m / 2 - 1] + v[m / 2]);
  };
  const double median = median_of(pair_ratios);
  const json& s = eight.summary["scalars"];
  json out = {{"case", "puncture"},
              {"n", n},
              {"threads", threads},
              {"tau_factor", tau_factor},
              {"seconds", eight.seconds},
              {"solve_seconds", s.value("multigrid_seconds", 0.0)},
              {"cycles", s.value("multigrid_cycles", 0.0)},
              {"factor", s.value("multigrid_factor", 0.0)},
              {"poisson_seconds", poisson.seconds},
              {"poisson_solve_seconds", poisson.summary["scalars"].value("multigrid_seconds", 0.0)},
              {"ratio", eight.seconds / poisson.seconds},
              {"pair_ratios", pair_ratios},
              {"median_pair_ratio", median},
              {"solve_ratio", s.value("multigrid_seconds", 0.0) /
                                  std::max(1e-300, poisson.summary["scalars"].value("multigrid_seconds", 0.0))},
              // The multigrid cycles alone (FMG and the cycles, no set-up or analysis), pair by pair.
              {"median_pair_solve_ratio", median_of(pair_solve_ratios)},
              // One V-cycle on the finest level after the FMG start (with its residual check), pair by
              // pair: the eight equations' cost per cycle, apart from how many cycles each needs.
              {"cycle_seconds", eight.cycle_seconds},
              {"poisson_cycles", poisson.summary["scalars"].value("multigrid_cycles", 0.0)},
              {"poisson_cycle_seconds", poisson.cycle_seconds},
              {"median_pair_cycle_ratio", median_of(pair_cycle_ratios)}};
  std::cout << out.dump() << std::endl;
  return 0;
}

// The seconds of one scheduled entry in a run directory's timers.tsv (bin, entry, calls, seconds).
double entry_seconds(const fs::path& timers, const std::string& entry) {
  std::ifstream in(timers);
  std::string bin, name, calls, seconds;
  double sum = 0;
  while (in >> bin >> name >> calls >> seconds)
    if (name == entry) sum += std::stod(seconds);
  return sum;
}

// The paper example (parfiles/paper_example.yaml: mu_bn = 3, xhat_A = 0.4668, rho_max = 0.09265,
// r_c = 1.92) at n intervals, dx = 3.84/n, the whole outer iteration to convergence, beside the
// Poisson benchmark at the same n in the same process (alternating, after one warm-up each). Peak
// RSS is the process's after the first binary run (before any Poisson run), set against the
// grid's fields (grid_bytes). The IRE's ANALYSIS time is reported apart (ire_seconds).
int binary(int n, int threads, int reps, const std::string& parfile) {
  if (n < 16 || (n & (n - 1)) != 0) {
    std::cerr << "bhnsid-bench binary: --n must be a power of 2 (intervals) >= 16, got " << n << "\n";
    return 2;
  }
  std::ifstream file(parfile);
  if (!file) {
    std::cerr << "bhnsid-bench binary: cannot read " << parfile << "\n";
    return 2;
  }
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  char dx[64];
  std::snprintf(dx, sizeof dx, "%.17g", 3.84 / n);
  const std::vector<std::string> overrides{"grid.n=" + std::to_string(n), std::string("grid.dx=") + dx,
                                           "run.threads=" + std::to_string(threads)};
  const std::string poisson_par = poisson_parfile(n - 1, threads, 1.0);
  const fs::path directory = fs::temp_directory_path() / ("bhnsid-bench-" + std::to_string(getpid()));
  Measured best{1e300, {}}, poisson{1e300, {}};
  double ire_seconds = 0, solve_seconds = 0, peak_rss = 0;
  std::vector<double> pair_ratios;
  for (int r = 0; r <= reps; ++r) {
    const Measured a = run_once(text, overrides, directory);
    if (r == 0) {
      rusage usage{};
      getrusage(RUSAGE_SELF, &usage);
      peak_rss = static_cast<double>(usage.ru_maxrss) * 1024.0;
    }
    const double ire = entry_seconds(directory / "timers.tsv", "ire.residuals");
    const double solve = entry_seconds(directory / "timers.tsv", "multigrid.solve");
    const Measured b = run_once(poisson_par, poisson_cycle, directory);
    if (r == 0) continue;
    if (a.seconds < best.seconds) best = a, ire_seconds = ire, solve_seconds = solve;
    if (b.seconds < poisson.seconds) poisson = b;
    pair_ratios.push_back(a.seconds / b.seconds);
  }
  fs::remove_all(directory);
  std::sort(pair_ratios.begin(), pair_ratios.end());
  const std::size_t m = pair_ratios.size();
  const double median = m % 2 ? pair_ratios[m / 2] : 0.5 * (pair_ratios[m / 2 - 1] + pair_ratios[m / 2]);
  const json& s = best.summary["scalars"];
  const double outer = best.summary.value("iterations", 0.0), cycles = s.value("multigrid_cycles_total", 0.0);
  const double grid_bytes = s.value("grid_bytes", 0.0);
  json out = {{"case", "binary"},
              {"n", n},
              {"threads", threads},
              {"parfile", parfile},
              {"seconds", best.seconds},
              {"ire_seconds", ire_seconds},
              {"outer_iterations", outer},
              {"cycles", cycles},
              {"cycles_per_outer_iteration", outer > 0 ? cycles / outer : 0.0},
              {"solve_seconds", solve_seconds},
              {"peak_rss_bytes", peak_rss},
              {"grid_bytes", grid_bytes},
              {"rss_over_grid", grid_bytes > 0 ? peak_rss / grid_bytes : 0.0},
              {"poisson_seconds", poisson.seconds},
              {"ratio", best.seconds / poisson.seconds},
              {"pair_ratios", pair_ratios},
              {"median_pair_ratio", median},
              {"sigma", s.value("sigma", 0.0)},
              {"omega_hat", s.value("omega_hat", 0.0)},
              {"bernoulli_constant", s.value("bernoulli_constant", 0.0)}};
  std::cout << out.dump() << std::endl;
  return 0;
}

int poisson(int n, int threads, int reps, double tau_factor, const std::vector<std::string>& overrides) {
  if (n < 3 || ((n + 1) & n) != 0) {
    std::cerr << "bhnsid-bench poisson: --n must be 2^k - 1 (vertex-centred multigrid: n + 1 intervals), got " << n
              << "\n";
    return 2;
  }
  const std::string par = poisson_parfile(n, threads, tau_factor);
  const fs::path directory = fs::temp_directory_path() / ("bhnsid-bench-" + std::to_string(getpid()));
  const Measured best = best_of(par, overrides, reps);
  // The reference: the same discretization solved to round-off level (not timed), so that the JSON
  // shows how close "discretization error" is: max_error / converged_max_error - 1.
  std::vector<std::string> reference_overrides = overrides;
  reference_overrides.push_back("multigrid.tau_factor=1e-6");
  reference_overrides.push_back("multigrid.max_cycles=60");
  const Measured reference = run_once(par, reference_overrides, directory);
  fs::remove_all(directory);
  const double converged_error = reference.summary["scalars"].value("error_max", 0.0);
  const json& s = best.summary["scalars"];
  const double points = static_cast<double>(n) * n * n;
  // A fused red-black sweep reads u and the source and writes u once per point (physics-free
  // Poisson: no coefficient arrays besides the source): 24 bytes, the floor of BASELINES.md.
  const double bytes_per_point_sweep = 24;
  const double sweep_seconds = s.value("multigrid_fine_sweep_seconds", 0.0);
  json out = {{"case", "poisson"},
              {"n", n},
              {"threads", threads},
              {"settings", overrides},
              {"seconds", best.seconds},
              {"solve_seconds", s.value("multigrid_seconds", 0.0)},
              {"cycles", s.value("multigrid_cycles", 0.0)},
              {"factor", s.value("multigrid_factor", 0.0)},
              {"max_error", s.value("error_max", 0.0)},
              {"converged_max_error", converged_error},
              {"error_excess", converged_error > 0 ? s.value("error_max", 0.0) / converged_error - 1 : 0.0},
              {"bytes_per_point_sweep", bytes_per_point_sweep},
              {"sweep_seconds", sweep_seconds},
              {"sweep_GBps", sweep_seconds > 0 ? bytes_per_point_sweep * points / sweep_seconds / 1e9 : 0.0}};
  std::cout << out.dump() << std::endl;
  return 0;
}

// Nested boxes, grid.boxes = 1 .. most, on mms's ball problem (mass 1, radius 0.5, its Robin
// condition about the ball's centre): the finest box [-1, 1]^3 of n intervals, each box more
// doubles the domain and adds n^3/2 points. One line per box count: the solve's wall time per
// stored point of the boxes, which stays flat when the composite cycle costs what a cube's does.
int boxes(int n, int most, int threads, int reps) {
  for (int b = 1; b <= most; ++b) {
    std::ostringstream par;
    par << "plugins: [grid, multigrid, mms]\n"
        << "run:\n  threads: " << threads << "\n"
        << "grid:\n  n: " << n << "\n  dx: " << 2.0 / n << "\n  boxes: " << b << "\n"
        << "multigrid:\n  tau_factor: 1e-3\n"
        << "mms:\n  problem: ball\n  robin_centre: [0.1, 0, 0]\n";
    const Measured m = best_of(par.str(), {}, reps);
    const json& s = m.summary["scalars"];
    const double points = static_cast<double>(b) * (n + 1) * (n + 1) * (n / 2 + 1);
    const double solve = s.value("multigrid_seconds", 0.0);
    json out = {{"case", "boxes"},
                {"n", n},
                {"boxes", b},
                {"threads", threads},
                {"domain_half_width", static_cast<double>(1 << (b - 1))},
                {"box_points", points},
                {"seconds", m.seconds},
                {"solve_seconds", solve},
                {"solve_ns_per_point", solve / points * 1e9},
                {"cycles", s.value("multigrid_cycles", 0.0)},
                {"factor", s.value("multigrid_factor", 0.0)},
                {"max_error", s.value("error_max", 0.0)}};
    std::cout << out.dump() << std::endl;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bhnsid-bench: benchmarks of the production solver path, one JSON line per case"};
  app.require_subcommand(1);
  int n = 255, threads = 1, reps = 3;
  // FMG and one V(2,2) cycle with omega = 1.2 stop at |r| <= |tau| with max_error 3.7 % above the
  // converged one at N = 63, 127 and 255; the default V(2,1) needs two cycles for that (1.0 %)
  // and takes 20 % longer. error_excess in the output shows the criterion is met.
  double tau_factor = 1.0;
  auto* p = app.add_subcommand("poisson", "the hypre peer's Poisson problem solved to discretization error");
  p->add_option("--n", n, "interior points per axis, 2^k - 1 (the peer's N)")->required();
  p->add_option("--threads", threads, "OpenMP threads")->check(CLI::PositiveNumber);
  p->add_option("--reps", reps, "timed runs after one warm-up; the best is reported")->check(CLI::PositiveNumber);
  p->add_option("--tau-factor", tau_factor, "stop when |r| <= this * |tau| (multigrid.tau_factor)");
  std::vector<std::string> user_overrides;
  p->add_option("--set", user_overrides, "override a parameter of the run, as bhnsid run --set (repeatable)")
      ->allow_extra_args(false);
  int pn = 128;
  auto* q = app.add_subcommand("puncture", "the eight equations of a boosted puncture beside Poisson at the same n");
  q->add_option("--n", pn, "intervals per axis, a power of 2")->required();
  q->add_option("--threads", threads, "OpenMP threads")->check(CLI::PositiveNumber);
  q->add_option("--reps", reps, "timed runs after one warm-up; the best is reported")->check(CLI::PositiveNumber);
  double puncture_tau = 1e-3;
  q->add_option("--tau-factor", puncture_tau,
                "both solves stop when |r| <= this * |tau| for every equation (the solver's default 1e-3; "
                "1 is the Poisson benchmark's criterion)");
  int bn = 128;
  std::string binary_parfile = std::string(BHNSID_SOURCE_DIR) + "/parfiles/paper_example.yaml";
  auto* bin = app.add_subcommand("binary", "the paper example's BH/NS binary to convergence beside Poisson at the same n");
  bin->add_option("--n", bn, "intervals per axis, a power of 2 (dx = 3.84/n: the file's r_c = 1.92)")->required();
  bin->add_option("--threads", threads, "OpenMP threads")->check(CLI::PositiveNumber);
  bin->add_option("--reps", reps, "timed runs after one warm-up; the best is reported")->check(CLI::PositiveNumber);
  bin->add_option("--parfile", binary_parfile, "the binary's parameter file (grid.n, grid.dx, run.threads are set)");
  int sweep_n = 256;
  auto* w = app.add_subcommand("sweep", "one vector sweep of core with a lower-order term, ns per point at n = 32 .. N");
  w->add_option("--n", sweep_n, "largest n (intervals), a power of 2 >= 32");
  w->add_option("--threads", threads, "OpenMP threads")->check(CLI::PositiveNumber);
  std::string sweep_lower = "none";
  w->add_option("--lower", sweep_lower, "lower-order term of the swept operator")
      ->check(CLI::IsMember({"none", "momentum", "shift", "shift-no-hole"}));
  int robin_n = 128;
  auto* b = app.add_subcommand("robin", "one relaxation and one residual of the outer-boundary rows, ms");
  b->add_option("--n", robin_n, "intervals per axis, a power of 2");
  b->add_option("--threads", threads, "OpenMP threads")->check(CLI::PositiveNumber);
  int split_n = 128;
  auto* cs = app.add_subcommand("colour-split",
                                "core's vector sweep (principal part) beside the same sweep on colour-split storage, ns per point");
  cs->add_option("--n", split_n, "intervals per axis, a power of 2 >= 32");
  cs->add_option("--threads", threads, "OpenMP threads")->check(CLI::PositiveNumber);
  int box_n = 64, most_boxes = 4;
  auto* nb = app.add_subcommand("boxes", "nested boxes 1 .. B on the ball problem: solve time per stored point");
  nb->add_option("--n", box_n, "intervals per side of every box, divisible by 4");
  nb->add_option("--boxes", most_boxes, "most boxes")->check(CLI::Range(1, 16));
  nb->add_option("--threads", threads, "OpenMP threads")->check(CLI::PositiveNumber);
  nb->add_option("--reps", reps, "timed runs after one warm-up; the best is reported")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  // A failed benchmark run is one line on stderr and exit 1.
  auto guarded = [](auto&& bench) {
    try {
      return bench();
    } catch (const std::exception& e) {
      std::cerr << "bhnsid-bench: " << e.what() << "\n";
      return 1;
    }
  };
  if (nb->parsed()) return guarded([&] { return boxes(box_n, most_boxes, threads, reps); });
  if (w->parsed()) return bhnsid::bench::vector_sweep(sweep_n, threads, sweep_lower);
  if (cs->parsed()) return bhnsid::bench::colour_split_sweep(split_n, threads);
  if (b->parsed()) return bhnsid::bench::robin_rows(robin_n, threads);
  if (q->parsed()) return guarded([&] { return puncture(pn, threads, reps, puncture_tau); });
  if (bin->parsed()) return guarded([&] { return binary(bn, threads, reps, binary_parfile); });
  // The benchmark's cycle; a --set of the same key, applied later, wins.
  std::vector<std::string> overrides = poisson_cycle;
  overrides.insert(overrides.end(), user_overrides.begin(), user_overrides.end());
  return guarded([&] { return poisson(n, threads, reps, tau_factor, overrides); });
}
