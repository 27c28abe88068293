// bhnsid validate with lapse_komar: the IRE evaluates maximal slicing on the alpha that the plugin
// builds from eta~ and its singular puncture term, so every equation, the lapse's included, must
// converge at second order away from the puncture; and a 1 % error in the shift's coupling to
// alpha's gradient must fail.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "validate_runs.hpp"

using namespace bhnsid::test;
using Catch::Detail::Approx;

namespace {

// boosted_puncture_komar.yaml (P_y = 0.3, virial condition) at n = 32, 64, 128 on r_c = 2.5, the
// excision cube on one lattice at every dx, solved far below the truncation error; the IRE added.
Validated validate_boosted_hole(const TempDir& dir, const std::string& extra_set) {
  std::vector<std::string> sets{"grid.n=32", "grid.dx=0.15625", "shift.excision_lattice=0.15625",
                                "multigrid.tau_factor=1e-6"};
  if (!extra_set.empty()) sets.push_back(extra_set);
  return validate(dir, (source_dir() / "parfiles" / "boosted_puncture_komar.yaml").string(), sets, {"--with", "ire"});
}

}  // namespace

TEST_CASE("plugins.lapse_komar.validate_boosted_hole", "[plugins][lapse_komar][ire]") {
  // Measured at the finest pair: Hamiltonian 2.02, lapse 2.02, momentum 2.01, shift 2.00.
  TempDir dir;
  const Validated v = validate_boosted_hole(dir, "");
  INFO(v.output);
  REQUIRE(v.exit_code == 0);
  CHECK(v.report["passed"].get<bool>());
  for (const std::string eq : {"hamiltonian", "lapse", "momentum", "shift"}) {
    INFO(eq);
    CHECK(v.order(eq) == Approx(2.0).margin(0.2));
  }
  const Validated bad = validate_boosted_hole(dir, "shift.test_coupling_scale=1.01");
  INFO(bad.output);
  CHECK(bad.exit_code == 1);
  CHECK(bad.verdict("shift").rfind("FAIL", 0) == 0);
}
