#include "star_runs.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "process.hpp"

namespace bhnsid::test {

namespace fs = std::filesystem;

namespace {

/// `bhnsid run parfiles/NAME --output OUT --set ...`, and summary.json's status and scalars.
struct Launched {
  ProcessResult process;
  std::string status;
  std::map<std::string, double> scalars;
};

Launched launch(const std::string& parfile, const fs::path& out, const std::vector<std::string>& sets) {
  std::vector<std::string> args{"run", (source_dir() / "parfiles" / parfile).string(), "--output", out.string()};
  for (const std::string& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  Launched l{run_bhnsid(args), {}, {}};
  if (fs::exists(out / "summary.json")) {
    const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
    l.status = summary.value("status", "");
    for (const auto& [key, value] : summary["scalars"].items()) l.scalars[key] = value.get<double>();
  }
  return l;
}

}  // namespace

StarRun run_static_star(int n, double dx, const std::vector<std::string>& sets, const std::string& parfile) {
  TempDir dir;
  const fs::path out = dir.path() / "star";
  std::vector<std::string> all{fmt::format("grid.n={}", n), fmt::format("grid.dx={}", dx)};
  all.insert(all.end(), sets.begin(), sets.end());
  const Launched l = launch(parfile, out, all);
  StarRun run;
  run.exit_code = l.process.exit_code;
  run.output = l.process.out + l.process.err;
  run.status = l.status;
  run.scalars = l.scalars;
  if (!fs::exists(out / "star_axis.tsv")) return run;
  // The axis row nearest xhat_C (header: "# sigma = ..., xhat_C = X; ...").
  std::istringstream lines(read_file(out / "star_axis.tsv"));
  std::string line;
  std::getline(lines, line);
  const double x_c = std::stod(line.substr(line.find("xhat_C = ") + 9));
  std::getline(lines, line);
  double best = 1e300;
  while (std::getline(lines, line)) {
    double x, rho0, chi, eta, alpha;
    std::istringstream(line) >> x >> rho0 >> chi >> eta >> alpha;
    if (std::fabs(x - x_c) < best) {
      best = std::fabs(x - x_c);
      run.chi_centre = chi;
      run.alpha_centre = alpha;
      run.has_axis = true;
    }
  }
  return run;
}

double ParfileRun::scalar(const std::string& key) const {
  const auto it = scalars.find(key);
  if (it == scalars.end()) throw std::out_of_range("summary.json has no scalar '" + key + "'\n" + output);
  return it->second;
}

ParfileRun run_parfile(const std::string& parfile, const std::vector<std::string>& sets) {
  TempDir dir;
  const fs::path out = dir.path() / "run";
  const Launched l = launch(parfile, out, sets);
  ParfileRun run;
  run.exit_code = l.process.exit_code;
  run.output = l.process.out + l.process.err;
  run.status = l.status;
  run.scalars = l.scalars;
  if (fs::exists(out / "fields_axis.tsv")) {
    std::istringstream lines(read_file(out / "fields_axis.tsv"));
    std::string line, name;
    std::getline(lines, line);
    std::istringstream head(line.substr(2));  // "# x\tchi..."
    std::vector<std::string> names;
    while (head >> name) names.push_back(name);
    while (std::getline(lines, line)) {
      std::istringstream row(line);
      for (const std::string& n : names) {
        double v;
        row >> v;
        run.axis[n].push_back(v);
      }
    }
  }
  return run;
}

std::vector<double> fixed_source_errors(double (*value)(const StarRun&), double reference) {
  std::vector<double> errors;
  for (const auto& [n, dx] : {std::pair{32, 0.12}, std::pair{64, 0.06}, std::pair{128, 0.03}}) {
    const StarRun r = run_static_star(n, dx, {"star.iterate=false"});
    if (r.exit_code != 0) throw std::runtime_error("the fixed-source run failed:\n" + r.output);
    errors.push_back(value(r) - reference);
  }
  return errors;
}

double tov01::bernoulli_constant() { return std::sqrt(1 - 2 * adm_mass / radius_areal); }

}  // namespace bhnsid::test
