// Truncation error of every manufactured problem: the discrete operator applied to the sampled
// exact solution, max over interior points of |L_h(u_exact)|, must fall by 4 when dx halves on the
// same cube (second-order stencils, analytic sources). A wrong source term or stencil coefficient
// leaves an O(1) remainder and fails this at once.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <vector>

#include "mms_test_support.hpp"

using namespace bhnsid;
using namespace bhnsid::mms;
using namespace bhnsid::mms::test;

namespace {

// max |L_h(u_exact)| of each equation on a cube of half-width rc with n intervals.
std::vector<double> truncation(Settings s, int n, double rc, bool z_symmetry) {
  MemoryGrid grid(n, 2 * rc / n, z_symmetry);
  Manufactured m(grid, s);
  m.set_exact();
  std::vector<double> out;
  for (EllipticEquation* eq : equations_of(m)) out.push_back(residual_of(*eq, grid).max_interior);
  return out;
}

// Runs n0, 2 n0, 4 n0 and checks both ratios of every equation; reports the numbers.
void check_second_order(const std::string& tag, const Settings& s, int n0, double rc, bool z_symmetry) {
  std::vector<std::vector<double>> t;
  for (int n : {n0, 2 * n0, 4 * n0}) t.push_back(truncation(s, n, rc, z_symmetry));
  for (std::size_t e = 0; e < t[0].size(); ++e) {
    const double r1 = t[0][e] / t[1][e], r2 = t[1][e] / t[2][e];
    std::ostringstream msg;
    msg << tag << " equation " << e << ": max|L_h(u_exact)| = " << t[0][e] << ", " << t[1][e] << ", " << t[2][e]
        << "; ratios " << r1 << ", " << r2;
    INFO(msg.str());
    CHECK(r1 == Approx(4.0).margin(0.4));
    CHECK(r2 == Approx(4.0).margin(0.4));
  }
}

}  // namespace

// Measured ratios (n = 16 -> 32 -> 64): poisson 4.001, 4.000; nonlinear 3.85, 3.96; vector
// 3.92, 3.92; ball 3.96, 3.97; coupled 3.85, 3.96 and 3.77, 3.94. The point-local terms (c u^5,
// kappa n n.V, a w, b u^3) add no truncation error, so changing c or kappa leaves the numbers as
// they are; a wrong analytic term for them would leave an O(1) remainder.

TEST_CASE("plugins.mms.truncation_poisson", "[plugins][mms]") {
  // The hypre peer's problem on its own grid (r_c = 1/2, n = 16, 32, 64, no symmetry).
  check_second_order("poisson", defaults(Problem::poisson), 16, 0.5, false);
}

TEST_CASE("plugins.mms.truncation_nonlinear", "[plugins][mms]") {
  // lap u + c u^5 + s with both signs of c, on the half cube the multigrid tests use (r_c = 1).
  Settings s = defaults(Problem::nonlinear);
  check_second_order("nonlinear c=-1", s, 16, 1.0, true);
  s.problem.nonlinear_c = 0.5;
  check_second_order("nonlinear c=+0.5", s, 16, 1.0, false);
}

TEST_CASE("plugins.mms.truncation_vector", "[plugins][mms]") {
  // The momentum operator (kappa = 0) with equatorial symmetry, which reaches into the ghost plane
  // through the mixed z derivatives, and with the point-coupling term on the full cube.
  Settings s = defaults(Problem::vector);
  check_second_order("vector kappa=0", s, 16, 1.0, true);
  s.problem.vector_coupling = 2.0;
  check_second_order("vector kappa=2", s, 16, 1.0, false);
}

TEST_CASE("plugins.mms.truncation_ball", "[plugins][mms]") {
  // The C^1 density keeps the truncation error O(h^2) at the ball's surface too.
  check_second_order("ball", defaults(Problem::ball), 16, 1.0, true);
}

TEST_CASE("plugins.mms.truncation_coupled", "[plugins][mms]") {
  // Both equations of the coupled pair, each applied to both exact unknowns.
  check_second_order("coupled", defaults(Problem::coupled), 16, 1.0, true);
}
