// The Kepler limit with the singular-term lapse, parfiles/kepler_komar.yaml: mu_bn = 1,
// rho_max = 0.01, xhat_A = 0.6, n = 128, dx = 0.02, d/M_tot ~ 210 (the configuration of
// kepler_limit.yaml, where the paper's lapse gives 1/2: tests/plugins/star/test_kepler.cpp).
#include <catch2/catch.hpp>

#include <cmath>

#include "star_runs.hpp"

using namespace bhnsid::test;
using Catch::Detail::Approx;

TEST_CASE("plugins.lapse_komar.kepler_limit_at_wide_separation", "[plugins][lapse_komar][binary]") {
  // Omega^2 d^3/M_tot = 1 - (3 - nu) M_tot/d at first post-Newtonian order (0.987 here) within 3 %
  // (the star's 10 points per radius and the faces inside the separation: measured 0.997), with
  // M_tot = M_irr + M_NS (the horizon's mass and the isolated star's) and d the coordinate distance
  // from the puncture to the density maximum; c of the virial condition close to 1 (weak field).
  const ParfileRun r = run_parfile("kepler_komar.yaml", {});
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const double m_bh = r.scalar("bh_irreducible_mass"), m_ns = r.scalar("ns_adm_mass"), m_tot = m_bh + m_ns;
  const double d = r.scalar("separation"), omega = r.scalar("omega");
  const double nu = m_bh * m_ns / (m_tot * m_tot);
  const double kepler = omega * omega * d * d * d / m_tot, first_pn = 1 - (3 - nu) * m_tot / d;
  INFO("d/M_tot = " << d / m_tot << ", Omega^2 d^3/M_tot = " << kepler << ", 1PN " << first_pn);
  CHECK(kepler == Approx(first_pn).epsilon(0.03));
  CHECK(r.scalar("lapse_komar_c") == Approx(1.0).margin(0.01));
  CHECK(r.scalar("lapse_komar_virial_ratio") == Approx(1.0).margin(1e-5));
}
