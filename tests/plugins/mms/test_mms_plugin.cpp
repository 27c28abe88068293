// What the plugin does around the equations: checks against the grid, the fields and services it
// registers, initial data, errors and the x-axis table (on the test grid), and the same through the
// real executable with plugins [grid, mms] and no solver, which leaves the initial data in place.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "bhnsid/core/errors.hpp"
#include "mms_test_support.hpp"
#include "process.hpp"

using namespace bhnsid;
using namespace bhnsid::mms;
using namespace bhnsid::mms::test;
using Catch::Matchers::Contains;

namespace {

int count_lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace

TEST_CASE("plugins.mms.setup_checks_the_grid", "[plugins][mms]") {
  // Input errors name the parameter: poisson is not even in z; the ball must sit on z = 0 under
  // equatorial symmetry and inside the cube (the boundary conditions assume vacuum at the faces).
  MemoryGrid half(8, 0.25, true);
  CHECK_THROWS_MATCHES(Manufactured(half, defaults(Problem::poisson)), core::InputError,
                       Catch::Matchers::Message(
                           "mms.problem = poisson needs grid.symmetry = none: its exact solution g(tx) g(ty) g(tz), "
                           "g(t) = t (1 - t) e^t, is not even in z"));
  Settings off_plane = defaults(Problem::ball);
  off_plane.problem.ball_centre = {0.1, 0, 0.2};
  CHECK_THROWS_WITH(Manufactured(half, off_plane),
                    Contains("mms.ball_centre = (0.1, 0, 0.2) lies off the plane z = 0"));
  Settings too_big = defaults(Problem::ball);
  too_big.problem.ball_radius = 0.95;
  CHECK_THROWS_WITH(Manufactured(half, too_big), Contains("mms.ball_radius = 0.95") && Contains("reaches the faces"));
  // The Robin centre likewise: on z = 0 under equatorial symmetry, and inside the cube.
  Settings robin_off_plane = defaults(Problem::ball);
  robin_off_plane.robin_centre = {0.2, 0, 0.3};
  CHECK_THROWS_WITH(Manufactured(half, robin_off_plane),
                    Contains("mms.robin_centre = (0.2, 0, 0.3) lies off the plane z = 0"));
  Settings robin_outside = defaults(Problem::ball);
  robin_outside.robin_centre = {1.0, 0, 0};
  CHECK_THROWS_WITH(Manufactured(half, robin_outside),
                    Contains("mms.robin_centre = (1, 0, 0) lies outside the cube |x_i| < 1"));
  MemoryGrid full(8, 0.25, false);
  CHECK_NOTHROW(Manufactured(full, defaults(Problem::poisson)));
  CHECK_NOTHROW(Manufactured(full, off_plane));
}

TEST_CASE("plugins.mms.fields_and_services", "[plugins][mms]") {
  // Unknowns and coefficients with their tensor kinds, and each service's name, unknown,
  // coefficients, boundary and excision mask as the solver reads them.
  SECTION("scalar problems") {
    MemoryGrid grid(8, 0.25, true);
    Settings s = defaults(Problem::nonlinear);
    s.excision_radius = 0.3;
    Manufactured m(grid, s);
    const EllipticEquation& eq = *m.equation();
    CHECK(eq.name() == "mms");
    CHECK(eq.unknown() == "mms_u");
    CHECK(eq.coefficients() == std::vector<std::string>{"mms_source"});
    CHECK(eq.boundary().kind == OuterBoundary::Kind::dirichlet);
    CHECK(eq.excision_mask() == "mms.excision");
    const std::vector<core::TensorKind> scalar{core::TensorKind::scalar};
    CHECK(grid.field_info(grid.field_id("mms_u")).components == scalar);
    CHECK(m.partner() == nullptr);

    MemoryGrid grid2(8, 0.25, true);
    Manufactured ball(grid2, defaults(Problem::ball));
    const OuterBoundary b = ball.equation()->boundary();
    CHECK(b.kind == OuterBoundary::Kind::robin);
    CHECK(b.u_inf == std::vector<double>{0.0});
    CHECK(b.centre == std::array<double, 3>{0, 0, 0});
    CHECK(ball.equation()->excision_mask().empty());
  }
  SECTION("vector") {
    MemoryGrid grid(8, 0.25, true);
    Manufactured m(grid, defaults(Problem::vector));
    CHECK(m.equation()->unknown() == "mms_v");
    const std::vector<core::TensorKind> kinds{core::TensorKind::vector_x, core::TensorKind::vector_y,
                                              core::TensorKind::vector_z};
    CHECK(grid.field_info(grid.field_id("mms_v")).components == kinds);
    CHECK(grid.field_info(grid.field_id("mms_source")).components == kinds);
  }
  SECTION("coupled") {
    MemoryGrid grid(8, 0.25, true);
    Manufactured m(grid, defaults(Problem::coupled));
    REQUIRE(m.partner() != nullptr);
    CHECK(m.partner()->name() == "mms_partner");
    CHECK(m.partner()->unknown() == "mms_w");
    CHECK(m.partner()->coefficients() == std::vector<std::string>{"mms_source_w"});
    CHECK(m.unknowns() == std::vector<std::string>{"mms_u", "mms_w"});
  }
}

TEST_CASE("plugins.mms.initial_data", "[plugins][mms]") {
  // Dirichlet problems start from the exact values on the faces and at excised points and
  // initial_guess elsewhere; V^z, odd in z, starts at 0 on the symmetry plane; the ball (Robin)
  // starts from initial_guess on the faces too.
  MemoryGrid grid(8, 0.25, true);
  Settings s = defaults(Problem::vector);
  s.initial_guess = 0.7;
  s.excision_radius = 0.3;
  s.excision_centre = {0.25, 0, 0};
  Manufactured m(grid, s);
  m.set_initial();
  const Level& lv = grid.finest();
  const int v = grid.field_id("mms_v");
  const std::uint8_t* excised = grid.mask(grid.mask_id("mms.excision"), 0);
  int faces = 0, holes = 0, plane = 0, guesses = 0;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j)
        for (int i = 0; i < lv.nx; ++i) {
          const double value = grid.data(v, c, 0)[lv.at(i, j, k)];
          const double exact = m.exact().value(0, c, {lv.x(i), lv.y(j), lv.z(k)});
          if (lv.on_outer_face(i, j, k)) {
            CHECK(value == exact);
            ++faces;
          } else if (excised[lv.at(i, j, k)]) {
            CHECK(value == exact);
            ++holes;
          } else if (c == 2 && k == 0) {
            CHECK(value == 0.0);
            ++plane;
          } else {
            CHECK(value == 0.7);
            ++guesses;
          }
        }
  CHECK(holes > 0);
  CHECK(plane > 0);
  CHECK(faces > 0);
  CHECK(guesses > 0);

  MemoryGrid grid2(8, 0.25, true);
  Settings b = defaults(Problem::ball);
  b.initial_guess = -0.3;
  Manufactured ball(grid2, b);
  ball.set_initial();
  CHECK(grid2.data(grid2.field_id("mms_u"), 0, 0)[lv.at(0, 3, 2)] == -0.3);
}

TEST_CASE("plugins.mms.errors_and_line", "[plugins][mms]") {
  // error_max and error_rms over every stored point and component: 0 for the exact solution; one
  // point off by d gives max d and rms d / sqrt(points x components). The x-axis table has a header
  // and one row per point of the axis (n + 1), with u and exact per unknown and component.
  MemoryGrid grid(8, 0.25, true);
  Manufactured m(grid, defaults(Problem::vector));
  m.set_exact();
  CHECK(m.errors(0).max == 0.0);
  CHECK(m.errors(0).rms == 0.0);
  const Level& lv = grid.finest();
  grid.data(grid.field_id("mms_v"), 1, 0)[lv.at(2, 3, 1)] += 1e-3;
  const double count = 3.0 * lv.nx * lv.ny * lv.nz;
  CHECK(m.errors(0).max == Approx(1e-3).epsilon(1e-12));
  CHECK(m.errors(0).rms == Approx(1e-3 / std::sqrt(count)).epsilon(1e-9));
  const std::string table = m.line_table();
  CHECK(first_line(table) == "# x\tv_x\texact_v_x\tv_y\texact_v_y\tv_z\texact_v_z");
  CHECK(count_lines(table) == 1 + 9);

  MemoryGrid g2(8, 0.25, false);
  Manufactured p(g2, defaults(Problem::poisson));
  p.set_exact();
  const std::string t2 = p.line_table();
  CHECK(first_line(t2) == "# x\tu\texact");
  std::istringstream rows(t2.substr(t2.find('\n') + 1));
  double x, u, exact;
  int n = 0;
  while (rows >> x >> u >> exact) {
    CHECK(u == exact);
    CHECK(exact == p.exact().value(0, 0, {x, 0, 0}));
    ++n;
  }
  CHECK(n == 9);

  MemoryGrid g3(8, 0.25, true);
  Manufactured c(g3, defaults(Problem::coupled));
  CHECK(first_line(c.line_table()) == "# x\tu\texact_u\tw\texact_w");
}

TEST_CASE("plugins.mms.runs_through_the_executable", "[plugins][mms]") {
  // bhnsid run with plugins [grid, mms] and no solver: SETUP, INITIAL, one loop pass, ANALYSIS and
  // OUTPUT run, so error_max is the initial data's error, max |u_exact| inside for poisson with
  // initial_guess 0 (the peer's max u = 0.08401 on the continuum, 0.0840 at the grid point nearest
  // t = 0.618 for n = 16). The poisson problem on the default equatorial grid is refused with exit
  // code 2 and the message naming both parameters.
  using namespace bhnsid::test;
  TempDir dir;
  const auto par = dir.write("mms.yaml", "plugins: [grid, mms]\n");
  const auto out = dir.path() / "poisson";
  const ProcessResult r = run_bhnsid({"run", par.string(), "--output", out.string(), "--set", "grid.n=16", "--set",
                                      "grid.dx=0.0625", "--set", "grid.symmetry=none", "--set", "mms.problem=poisson"});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  CHECK(summary["scalars"]["error_max"].get<double>() == Approx(0.0840).epsilon(0.01));
  CHECK(summary["scalars"].contains("error_rms"));
  CHECK_FALSE(summary["scalars"].contains("error_max_partner"));
  const std::string line = read_file(out / "mms_line.tsv");
  CHECK(first_line(line) == "# x\tu\texact");
  CHECK(count_lines(line) == 1 + 17);

  const ProcessResult bad =
      run_bhnsid({"run", par.string(), "--output", (dir.path() / "bad").string(), "--set", "mms.problem=poisson"});
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.out + bad.err, Contains("mms.problem = poisson needs grid.symmetry = none"));

  const auto coupled = dir.path() / "coupled";
  const ProcessResult rc =
      run_bhnsid({"run", par.string(), "--output", coupled.string(), "--set", "grid.n=8", "--set", "grid.dx=0.25",
                  "--set", "mms.problem=coupled"});
  INFO(rc.out << rc.err);
  REQUIRE(rc.exit_code == 0);
  const auto s2 = nlohmann::json::parse(read_file(coupled / "summary.json"));
  CHECK(s2["scalars"]["error_max_partner"].get<double>() > 0);
}
