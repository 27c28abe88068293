// The hamiltonian plugin: its point term against eq. ham_hat, and its solve against the TOV star.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "kernels.hpp"
#include "star_runs.hpp"

using namespace bhnsid;
using namespace bhnsid::test;
using Catch::Detail::Approx;

namespace {

struct Point {
  double puncture_phi, aa, energy;  ///< energy: rho_E as the star gives it
};

hamiltonian::Sources sources_of(const Point& p, double sigma) {
  hamiltonian::Sources s;
  s.puncture_phi = &p.puncture_phi;
  s.aa = &p.aa;
  s.matter.energy = &p.energy;
  s.matter.sigma2 = sigma * sigma;
  return s;
}

}  // namespace

TEST_CASE("plugins.hamiltonian.point_term_is_eq_ham_hat", "[plugins][hamiltonian]") {
  // N(chi) = phi^-7 AA / 8 + 2 pi sigma^2 phi^5 rho_E with phi = puncture part + chi and, for static
  // Gamma = 2 matter, rho_E = rho0 h - P = rho0 + rho0^2 (physics-notes §2.1, §2.2); its slope is
  // dN/dchi (checked by a central difference to 1e-7).
  const double rho0 = 0.07, sigma = 0.9, chi = 1.1;
  const Point p{0.3, 2.5, rho0 * (1 + 2 * rho0) - rho0 * rho0};
  const hamiltonian::HamiltonianTerm<true> term{sources_of(p, sigma)};
  const double phi = 0.3 + chi;
  const double expected = 2.5 / (8 * std::pow(phi, 7)) + 2 * std::numbers::pi * sigma * sigma * std::pow(phi, 5) * (rho0 + rho0 * rho0);
  const auto t = term.at(0, chi);
  CHECK(t.value == Approx(expected).epsilon(1e-14));
  const double d = 1e-6;
  CHECK(t.slope == Approx((term.at(0, chi + d).value - term.at(0, chi - d).value) / (2 * d)).epsilon(1e-7));
}

TEST_CASE("plugins.hamiltonian.puncture_term_stays_finite_at_the_hole", "[plugins][hamiltonian]") {
  // Near the puncture phi^-7 AA ~ r^3 (physics-notes §2.1): with puncture_phi = M/(2r) and the
  // Bowen-York AA ~ 9 P^2 / (2 r^4), the term must vanish like r^3 and never overflow.
  const double m = 1, mom = 0.5;
  double previous = 0;
  for (double r : {1e-2, 1e-4, 1e-8, 1e-16}) {
    const Point p{m / (2 * r), 9 * mom * mom / (2 * r * r * r * r), 0};
    const hamiltonian::HamiltonianTerm<false> term{sources_of(p, 1)};
    const auto t = term.at(0, 1.0);
    INFO("r = " << r << ": N = " << t.value);
    CHECK(std::isfinite(t.value));
    CHECK(std::isfinite(t.slope));
    // (1/8) AA phi^-7 with phi = m/(2r) + 1, written without overflow: AA (2r/(m + 2r))^7 / 8.
    CHECK(t.value == Approx(9 * mom * mom / (16 * std::pow(r, 4)) * std::pow(2 * r / (m + 2 * r), 7)).epsilon(1e-12));
    if (previous > 0) CHECK(t.value < previous);
    previous = t.value;
  }
}

TEST_CASE("plugins.hamiltonian.tov_source_gives_psi_tov_at_second_order", "[plugins][hamiltonian]") {
  // With the TOV density of rho_c = 0.1 held fixed at sigma = R_iso (star.iterate =
  // false), chi must be the TOV conformal factor: chi(0) -> psi_c = 1.15989819199 (tov.py,
  // physics-notes §6.1) with the error falling by 4 (3.4 .. 4.6) per halving of dx on one cube
  // (r_c = 1.92: the exterior is a pure monopole, which the Robin rows keep exactly).
  const std::vector<double> e = fixed_source_errors([](const StarRun& r) { return r.chi_centre; }, tov01::psi_center);
  INFO("chi(0) - psi_c: " << e[0] << ", " << e[1] << ", " << e[2]);
  CHECK(e[0] / e[1] == Approx(4.0).margin(0.6));
  CHECK(e[1] / e[2] == Approx(4.0).margin(0.6));
  CHECK(std::fabs(e[2]) < 2e-4);  // 1/16 of the dx = 0.12 error, with margin
}

TEST_CASE("plugins.hamiltonian.matter_coefficient_error_is_visible", "[plugins][hamiltonian]") {
  // The test-only factor 1 + 1e-2 on the matter term moves chi(0) by far more than the
  // discretization error at dx = 0.06 (2.3e-4): the TOV comparison above can fail.
  const StarRun good = run_static_star(64, 0.06, {"star.iterate=false"});
  const StarRun bad = run_static_star(64, 0.06, {"star.iterate=false", "hamiltonian.test_matter_scale=1.01"});
  REQUIRE(good.exit_code == 0);
  REQUIRE(bad.exit_code == 0);
  INFO("chi(0): " << good.chi_centre << " vs " << bad.chi_centre);
  CHECK(std::fabs(bad.chi_centre - good.chi_centre) > 5 * std::fabs(good.chi_centre - tov01::psi_center));
}
