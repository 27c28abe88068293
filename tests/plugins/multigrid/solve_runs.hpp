#pragma once
// Runs of grid + multigrid + mms through the real executable, as a user runs them, and what the
// tests read back: summary.json scalars and the x-axis line mms writes.
#include <array>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "process.hpp"

namespace bhnsid::test {

struct SolveRun {
  int exit_code = -1;
  std::filesystem::path directory;  ///< the run directory
  std::string log;
  nlohmann::json summary;
  std::vector<std::array<double, 3>> line;  ///< x, u, exact along the x axis
  double scalar(const std::string& name) const { return summary["scalars"].at(name).get<double>(); }
  /// u - exact at the line point nearest to x.
  double error_at(double x) const;
};

/// `settings`: "section.key" -> value, applied with --set on top of plugins [grid, multigrid, mms].
SolveRun solve(const TempDir& dir, const std::string& name, const std::map<std::string, std::string>& settings);

}  // namespace bhnsid::test
