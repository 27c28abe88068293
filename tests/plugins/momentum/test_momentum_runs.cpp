// The momentum plugin through the real executable: a manufactured solution solved by the multigrid,
// and the refusal of a run without chi or eta.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "process.hpp"

using namespace bhnsid::test;
using Catch::Detail::Approx;

namespace {

struct MomentumRun {
  int exit_code = -1;
  std::string output;
  nlohmann::json summary;
  double scalar(const std::string& name) const { return summary["scalars"].at(name).get<double>(); }
};

/// plugins [grid, multigrid, momentum_mms, momentum] on the cube r_c = 1.92 with n intervals.
MomentumRun run_mms(const TempDir& dir, int n, const std::vector<std::string>& sets = {}) {
  static int counter = 0;
  const std::string name = "mms_" + std::to_string(n) + "_" + std::to_string(counter++);
  const auto par = dir.write(name + ".yaml",
                             "plugins: [grid, multigrid, momentum_mms, momentum]\n"
                             "grid:\n  n: " + std::to_string(n) + "\n  dx: " + std::to_string(3.84 / n) + "\n");
  const auto out = dir.path() / name;
  std::vector<std::string> args{"run", par.string(), "--output", out.string(), "--plugin-path", test_plugin_dir().string()};
  for (const auto& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  const ProcessResult r = run_bhnsid(args);
  MomentumRun run;
  run.exit_code = r.exit_code;
  run.output = r.out + r.err;
  if (std::filesystem::exists(out / "summary.json")) run.summary = nlohmann::json::parse(read_file(out / "summary.json"));
  return run;
}

}  // namespace

TEST_CASE("plugins.momentum.manufactured_solution_converges_at_second_order", "[plugins][momentum]") {
  // With chi, eta, puncture_phi and a moving fluid whose J makes the smooth W_exact of mms/problem.hpp
  // an exact solution (Robin faces, r_c = 1.92), the solved W must approach W_exact at second order:
  // the max error falls by 4 (3.4 .. 4.6) per halving of dx, n = 32, 64, 128.
  TempDir dir;
  const MomentumRun r1 = run_mms(dir, 32), r2 = run_mms(dir, 64), r3 = run_mms(dir, 128);
  for (const MomentumRun* r : {&r1, &r2, &r3}) {
    INFO(r->output);
    REQUIRE(r->exit_code == 0);
  }
  const double e1 = r1.scalar("w_error_max"), e2 = r2.scalar("w_error_max"), e3 = r3.scalar("w_error_max");
  INFO("max |W - W_exact|: " << e1 << ", " << e2 << ", " << e3 << "; ratios " << e1 / e2 << ", " << e2 / e3);
  INFO("multigrid factor per V(2,2) cycle: " << r1.scalar("multigrid_factor") << ", " << r2.scalar("multigrid_factor")
                                             << ", " << r3.scalar("multigrid_factor") << "; cycles "
                                             << r1.scalar("multigrid_cycles") << ", " << r2.scalar("multigrid_cycles")
                                             << ", " << r3.scalar("multigrid_cycles"));
  CHECK(e1 / e2 == Approx(4.0).margin(0.6));
  CHECK(e2 / e3 == Approx(4.0).margin(0.6));
  CHECK(e3 < 0.01 * r3.scalar("w_exact_max"));
}

TEST_CASE("plugins.momentum.source_coefficient_error_breaks_convergence", "[plugins][momentum]") {
  // A 5 % error in the matter term (test_source_scale = 1.05 on 16 pi sigma^2 eta phi^10 chi^-7 J)
  // must leave an error that does not converge: the ratio between n = 64 and 128 falls outside the
  // 3.4 .. 4.6 that the convergence test accepts, so that test can fail.
  TempDir dir;
  const std::vector<std::string> bad{"momentum.test_source_scale=1.05"};
  const MomentumRun r2 = run_mms(dir, 64, bad), r3 = run_mms(dir, 128, bad);
  REQUIRE(r2.exit_code == 0);
  REQUIRE(r3.exit_code == 0);
  const double e2 = r2.scalar("w_error_max"), e3 = r3.scalar("w_error_max");
  INFO("with the 5 % error: max |W - W_exact| " << e2 << ", " << e3 << ", ratio " << e2 / e3);
  CHECK((e2 / e3 < 3.4 || e2 / e3 > 4.6));
}

// The issue asks for a multigrid factor of at most 0.2 per cycle. Measured here for the momentum
// equation alone at n = 128 (the eight-equation system with a non-zero W needs moving matter, which
// comes with the binary); multigrid_factor is the geometric mean over the cycles of the last solve.
TEST_CASE("plugins.momentum.multigrid_factor_w_cycle", "[plugins][momentum]") {
  // W(2,2) cycles (multigrid.cycle: W) must reduce the residual by 0.2 or better per cycle (measured
  // 0.03) and reach the error of the default V(2,2) solve.
  TempDir dir;
  const MomentumRun v = run_mms(dir, 128), w = run_mms(dir, 128, {"multigrid.cycle=W"});
  REQUIRE(v.exit_code == 0);
  REQUIRE(w.exit_code == 0);
  const double fw = w.scalar("multigrid_factor");
  INFO("W(2,2): " << fw << " per cycle, " << w.scalar("multigrid_cycles") << " cycles, " << w.scalar("multigrid_seconds") << " s");
  CHECK(w.scalar("w_error_max") == Approx(v.scalar("w_error_max")).epsilon(0.01));
  CHECK(fw <= 0.2);
}

TEST_CASE("plugins.momentum.multigrid_factor_v_cycle_regression_guard", "[plugins][momentum]") {
  // The 0.2 per cycle is NOT MET by the default V(2,2) cycle (measured 0.23 at n = 128;
  // V(2,1): 0.32-0.36; plugins/momentum/README.md): the first-order term -(LW)^ij d_j ln(eta chi^-7) is badly
  // smoothed on the coarse levels (h |d ln chi^7| ~ 1 at h >= 0.48); with constant chi and eta the
  // same problem converges at 0.07-0.11, with W or F cycles at 0.03-0.08 (the test above). This test
  // guards the measured V-cycle rate against regressions: at most 0.4 per cycle.
  TempDir dir;
  const MomentumRun v = run_mms(dir, 128);
  REQUIRE(v.exit_code == 0);
  const double fv = v.scalar("multigrid_factor");
  INFO("V(2,2): " << fv << " per cycle, " << v.scalar("multigrid_cycles") << " cycles, " << v.scalar("multigrid_seconds") << " s");
  CHECK(fv <= 0.4);
}

TEST_CASE("plugins.momentum.missing_chi_or_eta_is_refused", "[plugins][momentum]") {
  // Without the fields it reads (chi, eta, puncture_phi: the hamiltonian's and the lapse's) the run
  // must stop at SETUP with exit 1 and a message naming the missing field.
  TempDir dir;
  const auto bare = dir.write("bare.yaml", "plugins: [grid, multigrid, momentum]\ngrid:\n  n: 16\n  dx: 0.1\n");
  const ProcessResult r = run_bhnsid({"run", bare.string(), "--output", (dir.path() / "bare").string()});
  INFO(r.out + r.err);
  CHECK(r.exit_code == 1);
  CHECK((r.out + r.err).find("field 'chi' is missing") != std::string::npos);
  for (const std::string field : {"eta", "puncture_phi"}) {
    const auto par = dir.write("omit_" + field + ".yaml",
                               "plugins: [grid, multigrid, momentum_mms, momentum]\ngrid:\n  n: 16\n  dx: 0.24\n"
                               "momentum_mms:\n  omit: " + field + "\n");
    const ProcessResult o = run_bhnsid({"run", par.string(), "--output", (dir.path() / ("omit_" + field)).string(),
                                        "--plugin-path", test_plugin_dir().string()});
    INFO(o.out + o.err);
    CHECK(o.exit_code == 1);
    CHECK((o.out + o.err).find("field '" + field + "' is missing") != std::string::npos);
  }
}
