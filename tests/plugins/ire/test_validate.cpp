// bhnsid validate end to end: the static star and the boosted puncture converge at second order in
// every equation's IRE residual, and a 1 % error in one term of any equation plugin makes it fail.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "validate_runs.hpp"

using namespace bhnsid::test;
using Catch::Detail::Approx;

namespace {

std::string parfile(const std::string& name) { return (source_dir() / "parfiles" / name).string(); }

const std::vector<std::string> star{"grid.n=32", "grid.dx=0.12"};  // r_c = 1.92, n = 32, 64, 128
// r_c = 2.5, n = 32, 64, 128, the excision cube on the lattice of 0.15625 at every dx, solved far below
// the truncation error so that the residuals are the discretisation's.
const std::vector<std::string> puncture{"grid.n=32", "grid.dx=0.15625", "shift.excision_lattice=0.15625",
                                        "multigrid.tau_factor=1e-6"};

std::vector<std::string> with(std::vector<std::string> sets, const std::string& extra) {
  sets.push_back(extra);
  return sets;
}

}  // namespace

TEST_CASE("plugins.ire.validate_static_star", "[plugins][ire]") {
  // Measured: Hamiltonian 2.16, 2.00; lapse 2.15, 2.00 (L2 orders of the two pairs); momentum and
  // shift identically zero (no W, no beta); Bernoulli reported, not judged (physics-notes §7).
  TempDir dir;
  const Validated v = validate(dir, parfile("static_star.yaml"), star);
  INFO(v.output);
  REQUIRE(v.exit_code == 0);
  CHECK(v.report["passed"].get<bool>());
  CHECK(v.order("hamiltonian") == Approx(2.0).margin(0.2));
  CHECK(v.order("lapse") == Approx(2.0).margin(0.2));
  CHECK(v.verdict("momentum").rfind("exact", 0) == 0);
  CHECK(v.verdict("shift").rfind("exact", 0) == 0);
  CHECK(v.verdict("bernoulli").rfind("reported", 0) == 0);
  CHECK(v.report["axis_rescaled"]["hamiltonian"].size() == 3);
}

TEST_CASE("plugins.ire.validate_static_star_beside_a_boosted_hole", "[plugins][ire]") {
  // A star at rest in the coordinates beside a moving hole has v = beta/alpha: the momentum
  // constraint, the shift and the IRE must all see the same j^i = rho0 h W^2 v^i (the star's
  // projections). Before they were the star's, the IRE took v = 0 for a static star and its
  // momentum residual was 8 pi sigma^2 j^y, not converging. Measured (n = 32, 64, 128, L2 orders of
  // the finest pair): Hamiltonian 1.85, momentum 1.85, lapse 1.84, shift 2.00.
  TempDir dir;
  const Validated v = validate(dir, parfile("static_star_boosted_hole.yaml"), {});
  INFO(v.output);
  REQUIRE(v.exit_code == 0);
  CHECK(v.report["passed"].get<bool>());
  for (const std::string eq : {"hamiltonian", "momentum", "lapse", "shift"}) {
    INFO(eq);
    CHECK(v.order(eq) == Approx(2.0).margin(0.2));
  }
}

TEST_CASE("plugins.ire.validate_fails_for_a_one_percent_error_in_the_star", "[plugins][ire]") {
  // hamiltonian.test_matter_scale and lapse.test_matter_scale = 1.01 (their matter terms 1 % off):
  // measured orders -1.11 and 1.23 at the finest pair; exit 1.
  TempDir dir;
  for (const std::string eq : {"hamiltonian", "lapse"}) {
    std::string scale = eq;
    scale.append(".test_matter_scale=1.01");  // not eq + "...": GCC 12 warns falsely (-Wrestrict) on that
    const Validated v = validate(dir, parfile("static_star.yaml"), with(star, scale));
    INFO(eq << "\n" << v.output);
    CHECK(v.exit_code == 1);
    CHECK(v.verdict(eq).rfind("FAIL", 0) == 0);
    CHECK(v.order(eq) < 1.5);
  }
}

TEST_CASE("plugins.ire.validate_boosted_puncture", "[plugins][ire]") {
  // P_y = 0.3; every equation at second order away from the puncture (its region: the excision
  // cube widened by 2 points of the coarsest run, the same length at every dx): measured 2.02, 2.01,
  // 2.02, 2.01 at the finest pair. Then the shift's coupling term (6/phi)(...) d phi 1 % off
  // (shift.test_coupling_scale = 1.01) must fail: measured order 0.62. (A 1 % error in its Ahat term,
  // test_source_scale, is not seen at these sizes: phi^-6 makes that term small next to the hole.)
  TempDir dir;
  const Validated v = validate(dir, parfile("boosted_puncture.yaml"), puncture);
  INFO(v.output);
  REQUIRE(v.exit_code == 0);
  for (const std::string eq : {"hamiltonian", "momentum", "lapse", "shift"}) CHECK(v.order(eq) == Approx(2.0).margin(0.2));
  const Validated bad = validate(dir, parfile("boosted_puncture.yaml"), with(puncture, "shift.test_coupling_scale=1.01"));
  INFO(bad.output);
  CHECK(bad.exit_code == 1);
  CHECK(bad.verdict("shift").rfind("FAIL", 0) == 0);
}

TEST_CASE("plugins.ire.validate_momentum_on_manufactured_matter", "[plugins][ire]") {
  // W with moving matter is not in the star or the puncture: the manufactured configuration of the
  // momentum tests (test plugin momentum_mms, with puncture_phi = 0 so that gamma = chi^4 delta is a
  // physical metric) satisfies the momentum constraint, and only that (--only momentum). n = 48, 96,
  // 192 on r_c = 1.92: order 1.99; with momentum.test_source_scale = 1.01 the order falls to 0.65
  // (the 1 % error is the size of the truncation error at n = 96; coarser runs would not see it).
  TempDir dir;
  const auto par = dir.write("mms.yaml", "plugins: [grid, multigrid, momentum_mms, momentum]\n"
                                         "grid:\n  n: 48\n  dx: 0.08\nmultigrid:\n  tau_factor: 1.0e-6\n"
                                         "momentum_mms:\n  puncture_phi: 0\n");
  const std::vector<std::string> extra{"--only", "momentum", "--with", "ire", "--plugin-path", test_plugin_dir().string()};
  const Validated v = validate(dir, par.string(), {}, extra);
  INFO(v.output);
  REQUIRE(v.exit_code == 0);
  CHECK(v.order("momentum") == Approx(2.0).margin(0.2));
  CHECK(v.verdict("hamiltonian").rfind("reported", 0) == 0);
  const Validated bad = validate(dir, par.string(), {"momentum.test_source_scale=1.01"}, extra);
  INFO(bad.output);
  CHECK(bad.exit_code == 1);
  CHECK(bad.verdict("momentum").rfind("FAIL", 0) == 0);
}

TEST_CASE("plugins.ire.validate_refuses_bad_input", "[plugins][ire]") {
  // One clear message and exit 2: too few levels, an unknown equation for --only, a missing file, a
  // bad parameter in the file (checked once, before any run); a run that fails is exit 1 naming it.
  TempDir dir;
  struct Case {
    std::vector<std::string> args;
    std::string expect;
  };
  const std::string ss = parfile("static_star.yaml");
  const Case cases[] = {
      {{"--levels", "1"}, "--levels 1"},
      {{"--only", "bernoulli"}, "--only bernoulli"},
      {{"--set", "grid.dx=-1"}, "grid.dx"},
      {{"--set", "ire.surface_cells=x"}, "ire.surface_cells"},
  };
  for (const Case& c : cases) {
    const Validated v = validate(dir, ss, {}, c.args);
    INFO(v.output);
    CHECK(v.exit_code == 2);
    CHECK(v.output.find(c.expect) != std::string::npos);
  }
  // No plugin implements the residual evaluator: validate says so (and how to add one) before running.
  const Validated none = validate(dir, parfile("static_star_sly.yaml"), {});
  CHECK(none.exit_code == 2);
  CHECK(none.output.find("residual_evaluator") != std::string::npos);
  CHECK(none.output.find("--with") != std::string::npos);
  const Validated missing = validate(dir, (dir.path() / "nope.yaml").string(), {});
  CHECK(missing.exit_code == 2);
  CHECK(missing.output.find("nope.yaml") != std::string::npos);
  // rho_max above the fold: every run fails; validate stops at the first with its log named.
  const Validated failed = validate(dir, ss, {"grid.n=16", "grid.dx=0.24", "star.rho_max=0.5"});
  INFO(failed.output);
  CHECK(failed.exit_code == 1);
  CHECK(failed.output.find("level_0") != std::string::npos);
}

TEST_CASE("plugins.ire.validate_plots_take_names_as_they_are", "[plugins][ire]") {
  // The plot step ran through a shell: a parameter file named a';touch PWNED;'.yaml (default
  // output runs/a';touch PWNED;'_validate) executed the embedded command, and a quote in the
  // directory's name made the plots fail.
  TempDir dir;
  const auto par = dir.write("a';touch PWNED;'.yaml", "plugins: [grid, multigrid, momentum_mms, momentum]\n"
                                                       "grid:\n  n: 16\n  dx: 0.24\nmultigrid:\n  tau_factor: 1.0e-6\n"
                                                       "momentum_mms:\n  puncture_phi: 0\n");
  const ProcessResult r = run_bhnsid({"validate", par.string(), "--levels", "2", "--only", "momentum", "--with", "ire",
                                      "--plugin-path", test_plugin_dir().string()},
                                     dir.path());
  INFO(r.out << r.err);
  CHECK((r.exit_code == 0 || r.exit_code == 1));  // the verdict at n = 16, 32 is not what this tests
  CHECK_FALSE(std::filesystem::exists(dir.path() / "PWNED"));
  CHECK(r.err.find("plots were not made") == std::string::npos);
  CHECK(std::filesystem::exists(dir.path() / "runs" / "a';touch PWNED;'_validate" / "residual_momentum.png"));
}
