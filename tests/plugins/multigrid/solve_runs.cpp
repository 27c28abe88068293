#include "solve_runs.hpp"

#include <cmath>
#include <sstream>

namespace bhnsid::test {

double SolveRun::error_at(double x) const {
  const std::array<double, 3>* best = nullptr;
  for (const auto& row : line)
    if (!best || std::fabs(row[0] - x) < std::fabs((*best)[0] - x)) best = &row;
  return best ? (*best)[1] - (*best)[2] : NAN;
}

SolveRun solve(const TempDir& dir, const std::string& name, const std::map<std::string, std::string>& settings) {
  const std::filesystem::path par = dir.write(name + ".yaml", "plugins: [grid, multigrid, mms]\n");
  const std::filesystem::path out = dir.path() / name;
  std::vector<std::string> args{"run", par.string(), "--output", out.string()};
  for (const auto& [key, value] : settings) {
    args.push_back("--set");
    args.push_back(key + "=" + value);
  }
  const ProcessResult r = run_bhnsid(args);
  SolveRun run;
  run.exit_code = r.exit_code;
  run.directory = out;
  run.log = r.out + r.err;
  if (std::filesystem::exists(out / "summary.json")) run.summary = nlohmann::json::parse(read_file(out / "summary.json"));
  if (std::filesystem::exists(out / "mms_line.tsv")) {
    std::istringstream in(read_file(out / "mms_line.tsv"));
    std::string text;
    while (std::getline(in, text)) {
      if (text.empty() || text[0] == '#') continue;
      std::istringstream fields(text);
      std::array<double, 3> row{};
      fields >> row[0] >> row[1] >> row[2];
      run.line.push_back(row);
    }
  }
  return run;
}

}  // namespace bhnsid::test
