// bhnsid validate with lapse_komar: the IRE evaluates maximal slicing on the alpha that the plugin
// builds from eta~ and its singular puncture term, so every equation, the lapse's included, must
// converge at second order away from the puncture; and a 1 % error in the shift's coupling to
// alpha's gradient must fail.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "process.hpp"

using namespace bhnsid::test;
using Catch::Detail::Approx;

namespace {

struct Validated {
  int exit_code = -1;
  std::string output;
  nlohmann::json report;
  double order(const std::string& eq) const { return report["equations"][eq]["order_l2"].back().get<double>(); }
  std::string verdict(const std::string& eq) const { return report["equations"][eq]["verdict"].get<std::string>(); }
};

// boosted_puncture_komar.yaml (P_y = 0.3, virial condition) at n = 32, 64, 128 on r_c = 2.5, the
// excision cube on one lattice at every dx, solved far below the truncation error; the IRE added.
Validated validate_boosted_hole(const TempDir& dir, const std::string& name, const std::string& extra_set) {
  const auto out = dir.path() / name;
  std::vector<std::string> args{"validate",
                                (source_dir() / "parfiles" / "boosted_puncture_komar.yaml").string(),
                                "--with", "ire", "--output", out.string(), "--no-plots"};
  for (const std::string s : {"grid.n=32", "grid.dx=0.15625", "shift.excision_lattice=0.15625",
                              "multigrid.tau_factor=1e-6"})
    args.insert(args.end(), {"--set", s});
  if (!extra_set.empty()) args.insert(args.end(), {"--set", extra_set});
  const ProcessResult p = run_bhnsid(args);
  Validated v;
  v.exit_code = p.exit_code;
  v.output = p.out + p.err;
  if (std::filesystem::exists(out / "validate.json")) v.report = nlohmann::json::parse(read_file(out / "validate.json"));
  return v;
}

}  // namespace

TEST_CASE("plugins.lapse_komar.validate_boosted_hole", "[plugins][lapse_komar][ire]") {
  // Measured at the finest pair: Hamiltonian 2.02, lapse 2.02, momentum 2.01, shift 2.00.
  TempDir dir;
  const Validated v = validate_boosted_hole(dir, "good", "");
  INFO(v.output);
  REQUIRE(v.exit_code == 0);
  CHECK(v.report["passed"].get<bool>());
  for (const std::string eq : {"hamiltonian", "lapse", "momentum", "shift"}) {
    INFO(eq);
    CHECK(v.order(eq) == Approx(2.0).margin(0.2));
  }
  const Validated bad = validate_boosted_hole(dir, "bad", "shift.test_coupling_scale=1.01");
  INFO(bad.output);
  CHECK(bad.exit_code == 1);
  CHECK(bad.verdict("shift").rfind("FAIL", 0) == 0);
}
