// The lapse plugin: its point term against eq. maxslice_hat, and its solve against the TOV star.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "kernels.hpp"
#include "process.hpp"
#include "star_runs.hpp"

using namespace bhnsid;
using namespace bhnsid::test;
using Catch::Detail::Approx;

TEST_CASE("plugins.lapse.point_term_is_eq_maxslice_hat", "[plugins][lapse]") {
  // N(eta) = -eta [ (7/8) phi^-8 AA + 2 pi sigma^2 phi^4 (rho_E + 2S) ], and for static Gamma = 2
  // matter rho_E + 2S = rho0 + 7 rho0^2 (physics-notes §2.4, §4.5); slope -k.
  const double chi = 1.05, punc = 0.2, aa = 1.5, rho0 = 0.08, sigma = 0.8, eta = 0.7;
  const double press = rho0 * rho0, h = 1 + 2 * rho0;
  lapse::Sources s;
  s.chi = &chi;
  s.puncture_phi = &punc;
  s.aa = &aa;
  s.rho0 = &rho0;
  s.press = &press;
  s.enthalpy = &h;
  s.sigma2 = sigma * sigma;
  const lapse::LapseTerm<false> term{s};
  const double phi = chi + punc;
  const double k = 0.875 * aa / std::pow(phi, 8) + 2 * std::numbers::pi * sigma * sigma * std::pow(phi, 4) * (rho0 + 7 * rho0 * rho0);
  const auto t = term.at(0, eta);
  CHECK(t.value == Approx(-eta * k).epsilon(1e-14));
  CHECK(t.slope == Approx(-k).epsilon(1e-14));
}

TEST_CASE("plugins.lapse.tov_source_gives_alpha_tov_at_second_order", "[plugins][lapse]") {
  // With the TOV density of rho_c = 0.1 fixed at sigma = R_iso, alpha = eta/chi at the centre must
  // tend to the TOV central lapse 0.72037884898 (tov.py, physics-notes §6.1), the error falling by
  // 4 (3.4 .. 4.6) per halving of dx.
  const std::vector<std::string> fixed{"hydro_corotating.iterate=false"};
  const StarRun r1 = run_static_star(32, 0.12, fixed), r2 = run_static_star(64, 0.06, fixed),
                r3 = run_static_star(128, 0.03, fixed);
  for (const StarRun* r : {&r1, &r2, &r3}) {
    INFO(r->output);
    REQUIRE(r->exit_code == 0);
  }
  const double e1 = r1.alpha_centre - tov01::lapse_center, e2 = r2.alpha_centre - tov01::lapse_center,
               e3 = r3.alpha_centre - tov01::lapse_center;
  INFO("alpha(0) - alpha_c: " << e1 << ", " << e2 << ", " << e3);
  CHECK(e1 / e2 == Approx(4.0).margin(0.6));
  CHECK(e2 / e3 == Approx(4.0).margin(0.6));
  CHECK(std::fabs(e3) < 2e-4);  // 1/16 of the dx = 0.12 error, with margin
}

TEST_CASE("plugins.lapse.needs_the_hamiltonian_plugin", "[plugins][lapse]") {
  // The lapse reads chi: a parameter file without the hamiltonian plugin is refused before running.
  TempDir dir;
  const auto par = dir.write("p.yaml", "plugins: [grid, multigrid, lapse]\n");
  const ProcessResult r = run_bhnsid({"check", par.string()});
  INFO(r.out << r.err);
  CHECK(r.exit_code == 2);
  CHECK((r.out + r.err).find("equation.hamiltonian") != std::string::npos);
}
