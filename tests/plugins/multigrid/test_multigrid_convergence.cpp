// The multigrid solver on manufactured solutions (plugin mms), through the real executable:
// second-order convergence of the converged discrete solution (error ratio 4 +- 0.4 when dx halves
// on the same cube) and the measured convergence factor per cycle, for each kind of equation the
// physics needs. Grids stay small so the suite runs in seconds.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "solve_runs.hpp"

using namespace bhnsid::test;

namespace {

using Settings = std::map<std::string, std::string>;

std::string real(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

Settings grid(int n, double half_width, const std::string& symmetry) {
  return {{"grid.n", std::to_string(n)}, {"grid.dx", real(2 * half_width / n)}, {"grid.symmetry", symmetry}};
}

Settings with(Settings a, const Settings& b) {
  for (const auto& [k, v] : b) a[k] = v;
  return a;
}

// Runs n = n0, 2 n0, 4 n0 on one cube and checks the two error ratios; returns the runs.
std::vector<SolveRun> series(const TempDir& dir, const std::string& tag, int n0, double half_width,
                             const std::string& symmetry, const Settings& extra,
                             const std::string& error_scalar = "error_max") {
  std::vector<SolveRun> runs;
  for (int n : {n0, 2 * n0, 4 * n0}) {
    runs.push_back(solve(dir, tag + std::to_string(n), with(grid(n, half_width, symmetry), extra)));
    INFO(tag << " n = " << n << "\n" << runs.back().log);
    REQUIRE(runs.back().exit_code == 0);
    REQUIRE(runs.back().summary["status"] == "converged");
  }
  const double e0 = runs[0].scalar(error_scalar), e1 = runs[1].scalar(error_scalar), e2 = runs[2].scalar(error_scalar);
  INFO(tag << " " << error_scalar << ": " << e0 << ", " << e1 << ", " << e2 << "; ratios " << e0 / e1 << ", " << e1 / e2);
  CHECK(e0 / e1 == Approx(4.0).margin(0.4));
  CHECK(e1 / e2 == Approx(4.0).margin(0.4));
  return runs;
}

}  // namespace

TEST_CASE("plugins.multigrid.poisson_dirichlet", "[plugins][multigrid]") {
  // (a) The hypre peer's problem (unit cube, u = g(x)g(y)g(z), g = t(1-t)e^t, zero Dirichlet data).
  // Second order, and the V(2,1) cycle with the default over-relaxed red-black smoother reduces
  // the residual by at least 10 per cycle (issue target: factor <= 0.1).
  TempDir dir;
  const auto runs = series(dir, "poisson", 16, 0.5, "none", {{"mms.problem", "poisson"}});
  for (const auto& run : runs) {
    INFO(run.log);
    CHECK(run.scalar("multigrid_factor") <= 0.1);
  }
  // The peer's discretization error at N = 64 is 9.53e-6 (BASELINES.md); ours at N = 63 must be
  // of that size: the same second-order stencil on nearly the same grid.
  CHECK(runs[2].scalar("error_max") == Approx(9.53e-6).epsilon(0.1));
}

TEST_CASE("plugins.multigrid.nonlinear_hamiltonian_like", "[plugins][multigrid]") {
  // (b) Lap u + c u^5 = f, the shape of the Hamiltonian constraint, with equatorial symmetry.
  TempDir dir;
  const auto runs = series(dir, "nonlinear", 16, 1.0, "equatorial", {{"mms.problem", "nonlinear"}});
  for (const auto& run : runs) CHECK(run.scalar("multigrid_factor") <= 0.15);
}

TEST_CASE("plugins.multigrid.vector_operator", "[plugins][multigrid]") {
  // (c) Lap V^i + (1/3) d^i d_j V^j, the operator of the momentum and shift equations, relaxed
  // with 3x3 point solves; V^z odd across the symmetry plane.
  TempDir dir;
  const auto runs = series(dir, "vector", 16, 1.0, "equatorial", {{"mms.problem", "vector"}});
  for (const auto& run : runs) CHECK(run.scalar("multigrid_factor") <= 0.2);
}

TEST_CASE("plugins.multigrid.coupled_pair", "[plugins][multigrid]") {
  // (g) Two coupled nonlinear equations, each its own service, relaxed together: both unknowns
  // converge at second order.
  TempDir dir;
  series(dir, "coupled", 16, 1.0, "equatorial", {{"mms.problem", "coupled"}}, "error_max");
  series(dir, "coupled_w", 16, 1.0, "equatorial", {{"mms.problem", "coupled"}}, "error_max_partner");
}

TEST_CASE("plugins.multigrid.excision_mask", "[plugins][multigrid]") {
  // (e) A sphere of radius 0.3 held at the exact solution on every level: the solve converges
  // around it and stays second order.
  TempDir dir;
  series(dir, "excised", 16, 1.0, "equatorial",
         {{"mms.problem", "nonlinear"}, {"mms.excision_radius", "0.3"}, {"mms.excision_centre", "[0.2, 0, 0]"}});
}

TEST_CASE("plugins.multigrid.non_power_of_two_hierarchy", "[plugins][multigrid]") {
  // (h) n = 40, 80, 160 = 5 * 2^k: equatorial hierarchies ending at n = 10 (11 x 11 x 6 points,
  // solved directly), the paper's n = 160 included.
  TempDir dir;
  const auto runs = series(dir, "n160_", 40, 1.0, "equatorial", {{"mms.problem", "nonlinear"}});
  CHECK(runs[2].log.find("level 4: n =   10") != std::string::npos);
  CHECK(runs[2].scalar("multigrid_factor") <= 0.15);
}
