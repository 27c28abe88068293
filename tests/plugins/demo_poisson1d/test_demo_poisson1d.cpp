// demo_poisson1d through the real executable: convergence order, its example parameter file, the failure path
// and reproduction from a run's params.yaml.
#include <catch2/catch.hpp>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "process.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

fs::path example() { return source_dir() / "parfiles" / "demo_poisson1d.yaml"; }

json summary(const fs::path& run) { return json::parse(read_file(run / "summary.json")); }

int line_count(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

}  // namespace

TEST_CASE("plugins.demo_poisson1d.second_order_convergence", "[plugins][demo_poisson1d]") {
  // Centred differences are second order: with the algebraic error driven far below the truncation
  // error (residual tolerance 1e-11; 1e-12 lies under the round-off floor ~2.4e-12 at 129 points),
  // error_max falls by 4 +- 0.4 each time h is halved (points 33 -> 65 -> 129).
  TempDir dir;
  std::vector<double> errors;
  for (const int points : {33, 65, 129}) {
    const fs::path out = dir.path() / ("points" + std::to_string(points));
    const ProcessResult r =
        run_bhnsid({"run", example().string(), "--output", out.string(), "--set",
                    "demo_poisson1d.points=" + std::to_string(points), "--set", "demo_poisson1d.tolerance=1e-11",
                    "--set", "run.max_iterations=1000"});
    INFO("points " << points << "\n" << r.err);
    REQUIRE(r.exit_code == 0);
    const json s = summary(out);
    REQUIRE(s["status"] == "converged");
    CHECK(s["scalars"]["points"] == static_cast<double>(points));
    errors.push_back(s["scalars"]["error_max"].get<double>());
  }
  const double ratio_coarse = errors[0] / errors[1], ratio_fine = errors[1] / errors[2];
  INFO("error_max " << errors[0] << ", " << errors[1] << ", " << errors[2] << "; ratios " << ratio_coarse << ", "
                    << ratio_fine);
  CHECK(ratio_coarse == Approx(4.0).margin(0.4));
  CHECK(ratio_fine == Approx(4.0).margin(0.4));
}

TEST_CASE("plugins.demo_poisson1d.example_parfile_runs", "[plugins][demo_poisson1d]") {
  // parfiles/demo_poisson1d.yaml runs unchanged to status "converged" with exit 0 and leaves the complete
  // run directory: params.yaml, log.txt, timers.tsv, scalars.tsv, summary.json and solution.tsv.
  TempDir dir;
  const fs::path out = dir.path() / "demo_poisson1d";
  const ProcessResult r = run_bhnsid({"run", example().string(), "--output", out.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const json s = summary(out);
  CHECK(s["status"] == "converged");
  CHECK(s["iterations"].get<int>() >= 1);
  CHECK(s["scalars"]["residual"].get<double>() < 1e-10);
  CHECK(s["scalars"]["error_max"].get<double>() < 1e-3);
  for (const char* name : {"params.yaml", "log.txt", "timers.tsv", "scalars.tsv", "summary.json", "solution.tsv"})
    CHECK(fs::is_regular_file(out / name));
  CHECK_FALSE(fs::exists(out / "log.txt.partial"));
  const std::string solution = read_file(out / "solution.tsv");
  CHECK_THAT(solution, Contains("# x\tu\texact"));
  CHECK(line_count(solution) == 1 + 65);
}

TEST_CASE("plugins.demo_poisson1d.iteration_limit_fails_but_keeps_last_state", "[plugins][demo_poisson1d]") {
  // With run.max_iterations=2 the residual cannot reach the tolerance: exit 1, status "failed", no
  // error_max (ANALYSIS needs success), yet OUTPUT still writes solution.tsv from the last state.
  TempDir dir;
  const fs::path out = dir.path() / "limited";
  const ProcessResult r =
      run_bhnsid({"run", example().string(), "--output", out.string(), "--set", "run.max_iterations=2"});
  INFO(r.err);
  CHECK(r.exit_code == 1);
  const json s = summary(out);
  CHECK(s["status"] == "failed");
  CHECK(s["iterations"] == 2);
  CHECK_THAT(s["message"].get<std::string>(), Contains("did not converge in run.max_iterations = 2"));
  CHECK_FALSE(s["scalars"].contains("error_max"));
  REQUIRE(fs::is_regular_file(out / "solution.tsv"));
  CHECK(line_count(read_file(out / "solution.tsv")) == 1 + 65);
}

TEST_CASE("plugins.demo_poisson1d.params_yaml_reproduces_the_run", "[plugins][demo_poisson1d]") {
  // Running the resolved params.yaml of a run gives bit-for-bit the same error_max and solution.tsv.
  TempDir dir;
  const fs::path first = dir.path() / "first", second = dir.path() / "second";
  const ProcessResult r1 = run_bhnsid({"run", example().string(), "--output", first.string(), "--set",
                                       "demo_poisson1d.points=41", "--set", "demo_poisson1d.sweeps=7"});
  INFO(r1.err);
  REQUIRE(r1.exit_code == 0);
  const ProcessResult r2 = run_bhnsid({"run", (first / "params.yaml").string(), "--output", second.string()});
  INFO(r2.err);
  REQUIRE(r2.exit_code == 0);
  const json s1 = summary(first), s2 = summary(second);
  CHECK(s1["scalars"]["points"] == 41.0);
  CHECK(s2["scalars"]["error_max"].get<double>() == s1["scalars"]["error_max"].get<double>());
  CHECK(s2["iterations"] == s1["iterations"]);
  CHECK(read_file(second / "solution.tsv") == read_file(first / "solution.tsv"));
}
