// parfiles/tov.yaml through the real executable (needs the eos_polytrope plugin): the scalars of the
// rho0_c = 0.1 star and of the maximum-mass stars in summary.json, and tov_profile.tsv.
#include <catch2/catch.hpp>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "process.hpp"

using namespace bhnsid::test;
using Catch::Detail::Approx;
namespace fs = std::filesystem;

TEST_CASE("plugins.tov.parfile_runs", "[plugins][tov]") {
  // `bhnsid run parfiles/tov.yaml --set tov.central_density=0.1` exits 0 and reports the star of
  // physics-notes T1 (Gamma = 2, K = 1, rho0_c = 0.1): M = 0.126957417269, M0 = 0.135312727055,
  // R = 1.00473500683, R_iso = 0.873162703434, alpha_c = 0.72037884898, psi_c = 1.15989819199, all
  // from /work/shared/physics-checks/tov.py (tov.tov(0.1)), to 1e-9 relative; and, with
  // report_maximum (set in the parfile), (M0)_max = 0.179862 (Miller 2001, figure captions) at
  // rho0_c = 0.31824 (tov.py), M_max = 0.163727615102 (tov.py).
  TempDir dir;
  const fs::path out = dir.path() / "tov";
  const ProcessResult r = run_bhnsid({"run", (source_dir() / "parfiles" / "tov.yaml").string(), "--output",
                                      out.string(), "--set", "tov.central_density=0.1"});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  const auto& s = summary["scalars"];
  CHECK(s["adm_mass"].get<double>() == Approx(0.126957417269).epsilon(1e-9));
  CHECK(s["rest_mass"].get<double>() == Approx(0.135312727055).epsilon(1e-9));
  CHECK(s["radius_areal"].get<double>() == Approx(1.00473500683).epsilon(1e-9));
  CHECK(s["radius_isotropic"].get<double>() == Approx(0.873162703434).epsilon(1e-9));
  CHECK(s["lapse_center"].get<double>() == Approx(0.72037884898).epsilon(1e-9));
  CHECK(s["psi_center"].get<double>() == Approx(1.15989819199).epsilon(1e-9));
  CHECK(s["tov_mass_error_estimate"].get<double>() < 1e-8);
  CHECK(s["max_rest_mass"].get<double>() == Approx(0.179862).margin(5e-7));
  CHECK(s["max_rest_mass_central_density"].get<double>() == Approx(0.31824).epsilon(1e-4));
  CHECK(s["max_adm_mass"].get<double>() == Approx(0.163727615102).epsilon(1e-9));
  CHECK(s["max_adm_mass_central_density"].get<double>() == Approx(0.31824).epsilon(1e-3));

  // tov_profile.tsv: header, first row the centre (r_iso = 0, psi_c, alpha_c, rho0 = 0.1), last row
  // the exterior solution at 4 R_iso (psi = 1 + M/(2 r_iso), rho0 = 0).
  const std::string table = read_file(out / "tov_profile.tsv");
  REQUIRE(table.rfind("# r_iso\tr_areal\tpsi\talpha\trho0\n", 0) == 0);
  std::istringstream lines(table);
  std::string line, last;
  std::getline(lines, line);
  std::getline(lines, line);
  double r0, ra0, psi0, alpha0, rho0;
  std::istringstream(line) >> r0 >> ra0 >> psi0 >> alpha0 >> rho0;
  CHECK(r0 == 0.0);
  CHECK(psi0 == Approx(1.15989819199).epsilon(1e-9));
  CHECK(rho0 == 0.1);
  while (std::getline(lines, line)) last = line;
  double r1, ra1, psi1, alpha1, rho1;
  std::istringstream(last) >> r1 >> ra1 >> psi1 >> alpha1 >> rho1;
  CHECK(r1 == Approx(4 * 0.873162703434).epsilon(1e-9));
  CHECK(psi1 == Approx(1 + 0.126957417269 / (2 * r1)).epsilon(1e-9));
  CHECK(rho1 == 0.0);
}
