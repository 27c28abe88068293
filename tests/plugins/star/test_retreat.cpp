// Backtracking after a failed field solve (physics-notes §4.4, "if the next FAS solve diverges,
// halve (sigma - sigma_old) and retry"): the quick start with a deliberate step failure after the
// multigrid solve of iteration 5, twice in a row (the test plugin tp_step_failure). The core then
// runs RETREAT (the multigrid puts its unknowns back, the star its constants) and UPDATE again at
// 1/2, then at 1/4 of the step.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "process.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;

namespace {

/// star_history.tsv: iteration, sigma, omega_hat, bernoulli_constant, x_c, change, matter_points, step_fraction.
std::vector<std::vector<double>> star_history(const std::filesystem::path& run) {
  std::istringstream in(read_file(run / "star_history.tsv"));
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream row(line);
    rows.emplace_back();
    for (std::string cell; std::getline(row, cell, '\t');) rows.back().push_back(std::stod(cell));
  }
  return rows;
}

}  // namespace

TEST_CASE("plugins.star.failed_solve_retreats_with_half_steps", "[plugins][star][binary]") {
  TempDir dir;
  const std::string quickstart = read_file(source_dir() / "parfiles" / "quickstart.yaml");
  const auto at = quickstart.find("diagnostics,");
  REQUIRE(at != std::string::npos);
  std::string faulty = quickstart;
  faulty.replace(at, 12, "diagnostics, tp_step_failure,");
  faulty += "\ntp_step_failure:\n  fail_at: 5\n  failures: 2\n  converge_after: 0\n";
  const auto parfile = dir.write("faulty.yaml", faulty);
  const auto clean_run = dir.path() / "clean", faulty_run = dir.path() / "faulty";
  const ProcessResult clean = run_bhnsid({"run", (source_dir() / "parfiles" / "quickstart.yaml").string(), "--output",
                                          clean_run.string()});
  const ProcessResult r = run_bhnsid({"run", parfile.string(), "--output", faulty_run.string(), "--plugin-path",
                                      test_plugin_dir().string()});
  INFO(r.err);
  REQUIRE(clean.exit_code == 0);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.err, Contains("retreat 1 of at most 4") && Contains("retreat 2 of at most 4"));

  // Up to iteration 4 both runs are the same. The retreat puts the fields back to those of solve 4
  // (exactly: the copy is in double precision) and the star's constants to those after step 3, so
  // the redone step 4 lies a quarter of the way from step 3 to the clean run's step 4, in sigma,
  // Omegahat and C_B alike.
  const auto a = star_history(clean_run), b = star_history(faulty_run);
  REQUIRE(a.size() > 5);
  REQUIRE(b.size() > 5);
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t c = 1; c < 4; ++c) CHECK(b[i][c] == a[i][c]);
  CHECK(b[3][7] == 0.25);
  CHECK(b[4][7] == 1);
  for (std::size_t c = 1; c < 4; ++c) {
    INFO("column " << c);
    const double expected = a[2][c] + 0.25 * (a[3][c] - a[2][c]);
    CHECK(std::fabs(b[3][c] - expected) < 1e-12 * std::fabs(expected));
  }

  // The same fixed point: both runs stop within the outer tolerance (1e-6 per step, contracting by
  // about 0.67 per step, so within ~2e-6 of it).
  const auto sa = nlohmann::json::parse(read_file(clean_run / "summary.json"))["scalars"];
  const auto sb = nlohmann::json::parse(read_file(faulty_run / "summary.json"))["scalars"];
  for (const char* key : {"sigma", "omega_hat", "bernoulli_constant", "rest_mass", "bh_momentum_y", "adm_mass"}) {
    INFO(key);
    CHECK(std::fabs(sb[key].get<double>() / sa[key].get<double>() - 1) < 1e-5);
  }
}
