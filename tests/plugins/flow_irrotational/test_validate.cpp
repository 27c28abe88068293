// bhnsid validate on the irrotational star in a rotating frame (parfiles/static_star_irrotational.yaml,
// star.test_omega_hat = 0.05, n = 32, 64, 128 at r_c = 1.92, 8 to 33 points per stellar radius): the
// IRE's rest-mass conservation residual d_i[rho0 W phi^6 (alpha v^i - B^i)], with W and v from the
// flow's physical-only differences and the IRE's own D0 (the flow solves a cut-cell flux form),
// falls at second order inside the star with every field equation. Measured: continuity orders 2.08,
// 2.08 (8.4e-6, 2.0e-6, 4.7e-7); Hamiltonian 1.98, 2.00; lapse 1.97, 2.00; momentum 1.64, 1.86.
#include <catch2/catch.hpp>

#include "validate_runs.hpp"

using namespace bhnsid::test;
using Catch::Detail::Approx;

TEST_CASE("plugins.flow_irrotational.validate_conserves_rest_mass_at_second_order", "[plugins][flow_irrotational]") {
  TempDir dir;
  const Validated v = validate(dir, (source_dir() / "parfiles" / "static_star_irrotational.yaml").string(),
                               {"grid.n=32", "grid.dx=0.12", "star.test_omega_hat=0.05"});
  INFO(v.output);
  REQUIRE(v.exit_code == 0);
  CHECK(v.verdict("continuity") == "pass");
  CHECK(v.order("continuity") == Approx(2.0).margin(0.2));
  CHECK(v.order("hamiltonian") == Approx(2.0).margin(0.2));
  CHECK(v.order("lapse") == Approx(2.0).margin(0.2));
}
