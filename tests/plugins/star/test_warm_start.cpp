// A sequence's warm start (bhnsid run --warm-start): the quick start at (rho0)_max = 0.105 started
// from the converged quick start at 0.1 (its fields, the excision state, the hole and the star's
// sigma, Omegahat and C_B) reaches the fixed point a cold start at 0.105 reaches, in fewer outer
// iterations; a neighbour at another x_a (not steerable) is refused. The same from the next coarser
// run (n = 32 -> 64, dx halved): the fields interpolated, the excision rebuilt, the fixed point of
// the cold run on the finer lattice.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "process.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;
using nlohmann::json;

TEST_CASE("plugins.star.warm_start_from_a_neighbour_reaches_the_cold_fixed_point",
          "[plugins][star][binary][warm]") {
  TempDir dir;
  const std::string quickstart = (source_dir() / "parfiles" / "quickstart.yaml").string();
  const auto neighbour = dir.path() / "rho0.1", cold = dir.path() / "cold", warm = dir.path() / "warm";
  const ProcessResult a = run_bhnsid({"run", quickstart, "--output", neighbour.string()});
  INFO(a.err);
  REQUIRE(a.exit_code == 0);
  const ProcessResult c = run_bhnsid({"run", quickstart, "--output", cold.string(), "--set", "star.rho_max=0.105"});
  const ProcessResult w = run_bhnsid({"run", quickstart, "--output", warm.string(), "--set", "star.rho_max=0.105",
                                      "--warm-start", neighbour.string()});
  INFO(c.err);
  INFO(w.err);
  REQUIRE(c.exit_code == 0);
  REQUIRE(w.exit_code == 0);
  CHECK_THAT(read_file(warm / "log.txt"), Contains("warm start from") && Contains("star.rho_max"));
  const json sc = json::parse(read_file(cold / "summary.json")), sw = json::parse(read_file(warm / "summary.json"));
  // Both stop within the outer tolerance (1e-6 per step, contracting by ~0.67 per step) of one fixed point.
  for (const char* key : {"sigma", "omega_hat", "bernoulli_constant", "rest_mass", "bh_momentum_y", "adm_mass",
                          "bh_bare_mass"}) {
    INFO(key);
    CHECK(std::fabs(sw["scalars"][key].get<double>() / sc["scalars"][key].get<double>() - 1) < 1e-5);
  }
  // And not the neighbour's: rho_max 5 % higher moves the rest mass by percents.
  const json sa = json::parse(read_file(neighbour / "summary.json"));
  CHECK(std::fabs(sw["scalars"]["rest_mass"].get<double>() / sa["scalars"]["rest_mass"].get<double>() - 1) > 1e-2);
  const int cold_iterations = sc["iterations"].get<int>(), warm_iterations = sw["iterations"].get<int>();
  INFO("cold " << cold_iterations << ", warm " << warm_iterations << " iterations");
  CHECK(warm_iterations < cold_iterations);

  const ProcessResult other = run_bhnsid({"run", quickstart, "--output", (dir.path() / "xa").string(), "--set",
                                          "star.x_a=0.35", "--warm-start", neighbour.string()});
  CHECK(other.exit_code == 2);
  CHECK_THAT(other.err, Contains("star.x_a") && Contains("steerable"));
}

TEST_CASE("plugins.star.warm_start_from_the_coarser_lattice_reaches_the_cold_fixed_point",
          "[plugins][star][binary][warm]") {
  TempDir dir;
  const std::string quickstart = (source_dir() / "parfiles" / "quickstart.yaml").string();  // n = 32, dx = 0.12
  const auto coarse = dir.path() / "n32", cold = dir.path() / "cold", warm = dir.path() / "warm";
  const auto run = [&](const std::filesystem::path& out, std::vector<std::string> extra) {
    std::vector<std::string> args = {"run", quickstart, "--output", out.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const ProcessResult r = run_bhnsid(args);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    return json::parse(read_file(out / "summary.json"));
  };
  const json sa = run(coarse, {});
  const json sc = run(cold, {"--set", "grid.n=64", "--set", "grid.dx=0.06"});
  const json sw = run(warm, {"--set", "grid.n=64", "--set", "grid.dx=0.06", "--warm-start", coarse.string()});
  CHECK_THAT(read_file(warm / "log.txt"), Contains("the next coarser lattice") && Contains("grid.n 32 -> 64"));
  for (const char* key : {"sigma", "omega_hat", "bernoulli_constant", "rest_mass", "bh_momentum_y", "adm_mass",
                          "bh_bare_mass"}) {
    INFO(key);
    CHECK(std::fabs(sw["scalars"][key].get<double>() / sc["scalars"][key].get<double>() - 1) < 1e-5);
  }
  // Not the coarse run's fixed point: the truncation error of n = 32 is far above the tolerance.
  CHECK(std::fabs(sw["scalars"]["sigma"].get<double>() / sa["scalars"]["sigma"].get<double>() - 1) > 1e-4);
  const int cold_iterations = sc["iterations"].get<int>(), warm_iterations = sw["iterations"].get<int>();
  INFO("cold " << cold_iterations << ", warm " << warm_iterations << " iterations");
  CHECK(warm_iterations < cold_iterations);
}
