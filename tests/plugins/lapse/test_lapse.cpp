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
  // rho_E = rho0 h - P and S = 3P, as the star gives them for a static star.
  const double energy = rho0 * h - press, trace = 3 * press;
  s.matter.energy = &energy;
  s.matter.trace = &trace;
  s.matter.sigma2 = sigma * sigma;
  const lapse::LapseTerm<true> term{s};
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
  const std::vector<double> e = fixed_source_errors([](const StarRun& r) { return r.alpha_centre; }, tov01::lapse_center);
  INFO("alpha(0) - alpha_c: " << e[0] << ", " << e[1] << ", " << e[2]);
  CHECK(e[0] / e[1] == Approx(4.0).margin(0.6));
  CHECK(e[1] / e[2] == Approx(4.0).margin(0.6));
  CHECK(std::fabs(e[2]) < 2e-4);  // 1/16 of the dx = 0.12 error, with margin
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
