// puncture.mass_target = irreducible: the hole of a binary held at the apparent horizon's mass
// mu_bn M_NS (parfiles/binary_komar.yaml, lapse_komar and the horizon tracked every iteration).
#include <catch2/catch.hpp>

#include <cmath>

#include "process.hpp"
#include "star_runs.hpp"

using namespace bhnsid::test;
using Catch::Detail::Approx;

TEST_CASE("plugins.puncture.irreducible_mass_is_held_at_the_target", "[plugins][puncture][binary]") {
  // mu_bn = 1 at n = 32: the run converges with M_irr = M_NS to the loop's mass_tolerance (1e-7), the
  // bare mass below it (M_irr ~ M_bare (1 + M_NS/(2d))), the binding energies with M_irr and with the
  // puncture mass close (their masses agree at O(P^2, M/d)), and M_Komar = M_ADM for the lapse.
  const ParfileRun r = run_parfile("binary_komar.yaml", {});
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.status == "converged");
  const double m_irr = r.scalar("bh_irreducible_mass"), m_ns = r.scalar("ns_adm_mass");
  CHECK(m_irr == Approx(m_ns).epsilon(1e-6));
  CHECK(r.scalar("bh_bare_mass") < 0.995 * m_irr);
  CHECK(r.scalar("binding_energy_irreducible") == Approx(r.scalar("binding_energy_puncture")).margin(1e-4));
  CHECK(r.scalar("lapse_komar_virial_ratio") == Approx(1.0).margin(1e-5));
  CHECK(std::isfinite(r.scalar("bh_momentum_ratio_irreducible")));
}

TEST_CASE("plugins.puncture.irreducible_target_needs_a_tracked_horizon", "[plugins][puncture]") {
  // Without the horizon searched every outer iteration there is no M_irr to hold: refused at SETUP
  // (exit 2) naming the parameter; without a binary, refused before anything runs.
  const ParfileRun untracked = run_parfile("binary_komar.yaml", {"horizon.every_iteration=false"});
  INFO(untracked.output);
  CHECK(untracked.exit_code == 2);
  CHECK(untracked.output.find("puncture.mass_target = irreducible") != std::string::npos);
  CHECK(untracked.output.find("horizon.every_iteration: true") != std::string::npos);
  const ParfileRun alone = run_parfile("boosted_puncture_komar.yaml", {"puncture.mass_target=irreducible", "grid.n=16",
                                                                       "grid.dx=2.5"});
  INFO(alone.output);
  CHECK(alone.exit_code == 2);
  CHECK(alone.output.find("holds the hole of a binary") != std::string::npos);
}
