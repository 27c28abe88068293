// Nested boxes (grid.boxes > 1): the FAS cycle on a composite grid of boxes refined by 2 about the
// origin, each level of the hierarchy a box twice as wide as the one inside it, through the real
// executable on the ball problem of plugin mms (the potential of a ball of mass 1, radius 0.5,
// centred at b = (0.1, 0, 0); outside it exactly -M/|x - b|).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "solve_runs.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;

namespace {

using Settings = std::map<std::string, std::string>;

// The finest box [-1, 1]^3 (z >= 0) with n intervals; `boxes` boxes put the faces at 2^(boxes-1).
// The finest box [-w, w]^3 (z >= 0) with n intervals; `boxes` boxes put the faces at 2^(boxes-1) w.
// max_levels 0: as many levels as the coarsening allows.
Settings ball(int n, int boxes, const std::string& robin_centre, int max_levels = 0, double w = 1.0) {
  char dx[64];
  std::snprintf(dx, sizeof dx, "%.17g", 2.0 * w / n);
  return {{"grid.n", std::to_string(n)},
          {"grid.dx", dx},
          {"grid.boxes", std::to_string(boxes)},
          {"grid.max_levels", std::to_string(max_levels)},
          {"grid.symmetry", "equatorial"},
          {"mms.problem", "ball"},
          {"mms.robin_centre", robin_centre},
          {"multigrid.tau_factor", "1e-6"}};
}

}  // namespace

TEST_CASE("plugins.multigrid.nested_boxes_converge_at_second_order", "[plugins][multigrid]") {
  // The Robin condition about the ball's centre is exact for the exterior, so the error is the
  // discretisation's alone: the composite L2 error (each box's points outside the finer box,
  // weighted by volume) falls by 4 when every box is refined together, on two and three boxes
  // (measured 4.25, 4.10 and 4.37, 4.16; n = 16 is not yet asymptotic: 5.0, 5.2), and so does the
  // largest error, at the ball's centre (4.02, 4.01 and 4.03, 4.02).
  TempDir dir;
  for (int boxes : {2, 3}) {
    std::vector<double> rms, max;
    for (int n : {32, 64, 128}) {
      char name[32];
      std::snprintf(name, sizeof name, "b%dn%d", boxes, n);
      const SolveRun run = solve(dir, name, ball(n, boxes, "[0.1, 0, 0]"));
      INFO("boxes = " << boxes << ", n = " << n << "\n" << run.log);
      REQUIRE(run.exit_code == 0);
      REQUIRE(run.summary["status"] == "converged");
      // The cycle's convergence factor of the single cube survives the box interfaces.
      CHECK(run.scalar("multigrid_factor") <= 0.2);
      rms.push_back(run.scalar("error_rms"));
      max.push_back(run.scalar("error_max"));
    }
    INFO("boxes = " << boxes << ": error_rms " << rms[0] << ", " << rms[1] << ", " << rms[2] << "; error_max " << max[0]
                    << ", " << max[1] << ", " << max[2]);
    CHECK(rms[0] / rms[1] == Approx(4.0).margin(0.5));
    CHECK(rms[1] / rms[2] == Approx(4.0).margin(0.4));
    CHECK(max[0] / max[1] == Approx(4.0).margin(0.4));
    CHECK(max[1] / max[2] == Approx(4.0).margin(0.4));
  }
}

TEST_CASE("plugins.multigrid.nested_boxes_keep_the_finest_truncation_error", "[plugins][multigrid]") {
  // Three boxes of n = 32 against one cube of the same domain [-4, 4]^3 at the finest box's
  // spacing everywhere (n = 128, 21 times the points): the ball sits in the finest box and the
  // coarse boxes hold the harmonic exterior, so the largest error, at the ball's centre, is the
  // same to a few per cent (measured 0.02165 against 0.02062).
  TempDir dir;
  const SolveRun nested = solve(dir, "nested", ball(32, 3, "[0.1, 0, 0]"));
  const SolveRun single = solve(dir, "cube", ball(128, 1, "[0.1, 0, 0]", 0, 4.0));
  INFO(nested.log << single.log);
  REQUIRE(nested.exit_code == 0);
  REQUIRE(single.exit_code == 0);
  INFO("error_max nested " << nested.scalar("error_max") << ", single cube " << single.scalar("error_max"));
  CHECK(nested.scalar("error_max") == Approx(single.scalar("error_max")).epsilon(0.1));
}

TEST_CASE("plugins.multigrid.nested_boxes_push_the_boundary_error_out", "[plugins][multigrid]") {
  // The Robin condition about the origin misses the ball's dipole M b; the solution's error from it
  // is the harmonic M b x / (2 r_c^3) inside the domain, M b / (2 r_c^2) = 0.05 at the faces of
  // r_c = 1 (test robin_ball_error_splits). Its size in the finest box [-1, 1]^3 is the difference
  // between the solutions with the condition about the origin and about the ball's centre (exact
  // for the exterior): one, two and three boxes put the faces at r_c = 1, 2, 4 and it falls from
  // 0.05 at r_c = 1 (measured 0.046) by about 8 per box (1/r_c^3; measured 0.0044, 0.00054), far
  // below the discretisation error at n = 32 (0.02).
  TempDir dir;
  std::vector<double> boundary_part;
  for (int boxes : {1, 2, 3}) {
    char name[32];
    std::snprintf(name, sizeof name, "o%d", boxes);
    const SolveRun about_origin = solve(dir, name, ball(32, boxes, "[0, 0, 0]"));
    std::snprintf(name, sizeof name, "b%d", boxes);
    const SolveRun about_ball = solve(dir, name, ball(32, boxes, "[0.1, 0, 0]"));
    INFO(about_origin.log << about_ball.log);
    REQUIRE(about_origin.exit_code == 0);
    REQUIRE(about_ball.exit_code == 0);
    REQUIRE(about_origin.line.size() == about_ball.line.size());
    double largest = 0;
    for (std::size_t p = 0; p < about_origin.line.size(); ++p)
      largest = std::max(largest, std::fabs(about_origin.line[p][1] - about_ball.line[p][1]));
    boundary_part.push_back(largest);
  }
  INFO("boundary part in the finest box at r_c = 1, 2, 4: " << boundary_part[0] << ", " << boundary_part[1] << ", "
                                                             << boundary_part[2]);
  CHECK(boundary_part[0] == Approx(0.05).epsilon(0.2));
  CHECK(boundary_part[1] / boundary_part[2] == Approx(8.0).margin(2.0));
  CHECK(boundary_part[2] < 1e-3);
}

TEST_CASE("plugins.multigrid.nested_boxes_refuse_bad_layouts", "[plugins][multigrid]") {
  TempDir dir;
  SECTION("n not divisible by 4") {
    const SolveRun run = solve(dir, "odd", ball(18, 2, "[0.1, 0, 0]"));
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.log, Contains("grid.n = 18 with grid.boxes = 2") && Contains("divisible by 4"));
  }
  SECTION("fewer levels than boxes") {
    const SolveRun run = solve(dir, "levels", ball(16, 3, "[0.1, 0, 0]", 2));
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.log, Contains("grid.max_levels = 2 is below grid.boxes = 3"));
  }
}
