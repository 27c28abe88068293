// Maximum masses of the four piecewise-polytrope presets (plugins/eos_piecewise_polytrope) through the
// real executable: `bhnsid run` with plugins [eos_piecewise_polytrope, tov] and tov.report_maximum.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "process.hpp"

using namespace bhnsid::test;
using Catch::Detail::Approx;
namespace fs = std::filesystem;

TEST_CASE("plugins.tov.piecewise_presets_maximum_mass", "[plugins][tov]") {
  // Published: Read, Lackey, Owen & Friedman, PRD 79, 124032 (2009), Table III, column M_max:
  // SLy 2.049, APR4 2.213, H4 2.032, MS1 2.774 M_sun. Measured here (units G = c = M_sun = 1, so
  // max_adm_mass is in M_sun): 2.048411, 2.188001, 2.013851, 2.752777, i.e. -0.03 %, -1.13 %, -0.89 %,
  // -0.77 %. These numbers are those of the fit parameters themselves: an independent integration
  // (piecewise_max_mass_reference.py next to this file: its own EOS construction from Tables II and
  // III, TOV in Schwarzschild coordinates in r with scipy's DOP853, rtol 1e-11) gives the same four to
  // 1e-11, and the eos plugin's own RK4 test 2.048, 2.188, 2.014, 2.753. So the ~1 % residual for
  // APR4, H4 and MS1 is not numerical: it is most plausibly the fit's error against the tabulated EOS,
  // i.e. Table III's M_max column would be that of the tabulated EOS (SLy fits best: the crust is
  // SLy's). That reading is NOT verified here: the table could not be re-read with the tools at hand,
  // and the 0.5 % once expected for the fit's own masses does not hold. Tolerances: 1.5 % against
  // Table III (the ~1 % accuracy of the fits, with margin over the largest measured, 1.13 %), and
  // 1e-8 relative against the independent integration (its error is ~1e-11; the golden-section search
  // here locates rho_c to 1e-9 in ln rho_c, which costs only ~1e-18 in M at the maximum).
  struct Case {
    const char* preset;
    double table_iii, independent;
  };
  const Case cases[] = {{"sly", 2.049, 2.04841127153011},
                        {"apr4", 2.213, 2.188001070262705},
                        {"h4", 2.032, 2.0138513946569665},
                        {"ms1", 2.774, 2.7527768419458503}};
  for (const Case& c : cases) {
    TempDir dir;
    const fs::path par = dir.write("pp.yaml", std::string("plugins: [eos_piecewise_polytrope, tov]\n") +
                                                  "eos_piecewise_polytrope: {preset: " + c.preset + "}\n" +
                                                  "tov: {report_maximum: true, central_density: 0.002, "
                                                  "search_density_min: 1.0e-4, search_density_max: 0.02}\n");
    const fs::path out = dir.path() / "run";
    const ProcessResult r = run_bhnsid({"run", par.string(), "--output", out.string()});
    INFO(c.preset << ": " << r.out << r.err);
    REQUIRE(r.exit_code == 0);
    const auto s = nlohmann::json::parse(read_file(out / "summary.json"))["scalars"];
    const double m_max = s["max_adm_mass"].get<double>();
    INFO(c.preset << ": M_max = " << m_max << " M_sun, " << 100 * (m_max / c.table_iii - 1)
                  << " % from Table III, at rho_c = " << s["max_adm_mass_central_density"].get<double>());
    CHECK(std::fabs(m_max / c.table_iii - 1) < 0.015);
    CHECK(m_max == Approx(c.independent).epsilon(1e-8));
    // The maximum rest mass lies at the same central density (turning-point theorem).
    CHECK(s["max_rest_mass_central_density"].get<double>() ==
          Approx(s["max_adm_mass_central_density"].get<double>()).epsilon(1e-4));
  }
}
