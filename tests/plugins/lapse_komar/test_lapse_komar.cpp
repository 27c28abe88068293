// The lapse_komar plugin: its point term, the static lapse of a lone hole, the virial condition of a
// boosted hole, and its refusals.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "kernels.hpp"
#include "process.hpp"
#include "star_runs.hpp"

using namespace bhnsid;
using namespace bhnsid::test;
using Catch::Detail::Approx;

namespace {

ParfileRun hole(int n, double dx, double p, const std::string& condition) {
  char exact_dx[32];
  std::snprintf(exact_dx, sizeof exact_dx, "%.17g", dx);
  ParfileRun r = run_parfile("boosted_puncture_komar.yaml",
                             {"grid.n=" + std::to_string(n), std::string("grid.dx=") + exact_dx,
                              "puncture.momentum=[0," + std::to_string(p) + ",0]", "lapse_komar.condition=" + condition});
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return r;
}

}  // namespace

TEST_CASE("plugins.lapse_komar.point_term_is_maximal_slicing_for_eta", "[plugins][lapse_komar]") {
  // N(eta~) = -kappa (eta~ - c puncture_phi) is -kappa eta of eq. maxslice_hat with eta = eta~ - c
  // puncture_phi (the Laplacian of the puncture term vanishes), slope -kappa; alpha = eta / phi.
  const double chi = 1.05, punc = 0.2, aa = 1.5, rho0 = 0.08, sigma = 0.8, eta_regular = 0.9, c = 0.93;
  const double press = rho0 * rho0, h = 1 + 2 * rho0, energy = rho0 * h - press, trace = 3 * press;
  lapse_komar::Sources s;
  s.chi = &chi;
  s.puncture_phi = &punc;
  s.aa = &aa;
  s.matter.energy = &energy;
  s.matter.trace = &trace;
  s.matter.sigma2 = sigma * sigma;
  s.c = c;
  const double phi = chi + punc, eta = eta_regular - c * punc;
  const double kappa = 0.875 * aa / std::pow(phi, 8) + 2 * std::numbers::pi * sigma * sigma * std::pow(phi, 4) * (rho0 + 7 * rho0 * rho0);
  const auto t = lapse_komar::KomarTerm<true>{s}.at(0, eta_regular);
  CHECK(t.value == Approx(-eta * kappa).epsilon(1e-14));
  CHECK(t.slope == Approx(-kappa).epsilon(1e-14));
  CHECK(lapse_komar::alpha_of(eta_regular, chi, punc, c) == Approx(eta / phi).epsilon(1e-15));
  // A lone hole (eta~ = chi = 1, c = 1): the static Schwarzschild lapse, 0 on r = M/2, -1 at the puncture.
  CHECK(lapse_komar::alpha_of(1.0, 1.0, 1.0, 1.0) == 0.0);
  CHECK(lapse_komar::alpha_of(1.0, 1.0, 1e12, 1.0) == Approx(-1.0).epsilon(1e-11));
}

TEST_CASE("plugins.lapse_komar.lone_hole_gets_the_static_lapse", "[plugins][lapse_komar]") {
  // P = 0: kappa = 0, so eta~ = 1 and (with virial) c = 1 to round-off; alpha on the x axis is
  // (1 - M/2r)/(1 + M/2r) (negative inside r = M/2), and the Komar mass equals the ADM mass.
  for (const std::string condition : {"virial", "static"}) {
    INFO(condition);
    const ParfileRun r = hole(32, 1.25, 0.0, condition);
    CHECK(r.scalar("eta_regular_deviation_max") < 1e-13);
    CHECK(r.scalar("lapse_komar_c") == Approx(1.0).epsilon(1e-13));
    CHECK(r.scalar("lapse_komar_virial_ratio") == Approx(1.0).epsilon(1e-12));
    // diagnostics' fit of alpha itself sees the exact (1 - M/2r)/(1 + M/2r) = 1 - M/r + M^2/(2 r^2) -
    // M^3/(4 r^3) ... on surfaces at 10-20 M: the B + C/s + D/s^2 fit leaves O(M^3/s^3), measured 2.5e-5.
    CHECK(r.scalar("virial_ratio") == Approx(1.0).margin(1e-4));
    const auto& x = r.axis.at("x");
    const auto& alpha = r.axis.at("alpha");
    REQUIRE(x.size() == alpha.size());
    int negative = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double m_2r = 0.5 / std::fabs(x[i] - 0.1);
      CHECK(alpha[i] == Approx((1 - m_2r) / (1 + m_2r)).margin(1e-13));
      negative += alpha[i] < 0;
    }
    CHECK(negative > 0);  // the points at |x - 0.1| = 0.35 lie inside the horizon r = 0.5
  }
}

TEST_CASE("plugins.lapse_komar.boosted_hole_meets_the_virial_condition", "[plugins][lapse_komar]") {
  // P = 0.3: the virial condition moves c off 1 until M_Komar = M_ADM (as the lapse measures them, to
  // the update's tolerance); the static lapse misses it by the boost's O(P^2) share.
  const ParfileRun virial = hole(32, 1.25, 0.3, "virial");
  const ParfileRun fixed = hole(32, 1.25, 0.3, "static");
  INFO("c = " << virial.scalar("lapse_komar_c") << ", static ratio " << fixed.scalar("lapse_komar_virial_ratio"));
  CHECK(virial.scalar("lapse_komar_virial_ratio") == Approx(1.0).margin(1e-6));
  CHECK(std::fabs(virial.scalar("lapse_komar_c") - 1.0) > 1e-4);
  CHECK(fixed.scalar("lapse_komar_c") == 1.0);
  CHECK(std::fabs(fixed.scalar("lapse_komar_virial_ratio") - 1.0) > 1e-4);
  // diagnostics' independent fit of alpha agrees with the lapse's own (eta and phi) to its truncation.
  CHECK(virial.scalar("virial_ratio") == Approx(1.0).margin(1e-3));
}

TEST_CASE("plugins.lapse_komar.needs_a_puncture_and_a_known_condition", "[plugins][lapse_komar]") {
  // The singular term is the hole's: without a puncture plugin the parameter file is refused, and
  // so is a condition that is neither virial nor static.
  TempDir dir;
  const auto alone = dir.write("alone.yaml", "plugins: [grid, multigrid, hamiltonian, lapse_komar]\n");
  const ProcessResult r = run_bhnsid({"check", alone.string()});
  INFO(r.out << r.err);
  CHECK(r.exit_code == 2);
  CHECK((r.out + r.err).find("requires capability 'puncture'") != std::string::npos);
  const ProcessResult bad = run_bhnsid({"check", (source_dir() / "parfiles" / "boosted_puncture_komar.yaml").string(), "--set",
                                        "lapse_komar.condition=keplerian"});
  INFO(bad.out << bad.err);
  CHECK(bad.exit_code == 2);
  CHECK((bad.out + bad.err).find("lapse_komar.condition") != std::string::npos);
}
