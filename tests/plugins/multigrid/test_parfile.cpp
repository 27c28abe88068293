// parfiles/mms_nonlinear.yaml, the shipped example of an elliptic solve, runs unchanged.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "process.hpp"

using namespace bhnsid::test;

TEST_CASE("plugins.multigrid.example_parfile_runs", "[plugins][multigrid]") {
  // Converged, with the multigrid scalars and history, and an error of the size second order
  // predicts: the n = 16, 32, 64 series of nonlinear_hamiltonian_like ends near 3.5e-4 on this cube.
  TempDir dir;
  const auto out = dir.path() / "example";
  const ProcessResult r =
      run_bhnsid({"run", (source_dir() / "parfiles" / "mms_nonlinear.yaml").string(), "--output", out.string()});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  CHECK(summary["status"] == "converged");
  const auto& s = summary["scalars"];
  CHECK(s["multigrid_cycles"].get<double>() >= 1);
  CHECK(s["multigrid_factor"].get<double>() < 0.15);
  CHECK(s["multigrid_residual_mms"].get<double>() <= 1e-3 * s["multigrid_tau_mms"].get<double>());
  CHECK(s["error_max"].get<double>() < 1e-3);
  CHECK(std::filesystem::is_regular_file(out / "multigrid_history.tsv"));
  CHECK(std::filesystem::is_regular_file(out / "mms_line.tsv"));
}
