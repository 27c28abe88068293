// The black hole of a binary, set from the star (physics-notes §1.4, §4.6): the balancing momentum
// on analytic matter, and the initial hole scaled to the TOV star.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>
#include <numbers>

#include "binary.hpp"
#include "grid_fill.hpp"
#include "process.hpp"
#include "real_grid.hpp"
#include "test_fluid.hpp"

using namespace bhnsid;
using Catch::Detail::Approx;

TEST_CASE("plugins.puncture.balancing_momentum_of_moving_dust", "[plugins][puncture]") {
  // phi = 1, alpha = 1, dust (P = 0, h = 1) of density a exp(-r^2/s^2) moving with V = (0, v, 0):
  // j^y = rho0 W^2 v, W^2 = 1/(1 - v^2), so Phat_y = -sigma^2 v/(1 - v^2) a pi^(3/2) s^3 (the
  // trapezoid rule on the decayed Gaussian: far below 1e-8 at n = 32).
  auto g = test::equatorial_grid(32, 0.125, {fields::chi, fields::eta, fields::puncture_phi});
  test::FieldVelocityFluid fluid;
  fluid.sigma_value = 1.7;
  fluid.attach(*g);
  const double a = 0.03, s = 0.4, v = 0.2;
  test::fill(*g, fields::chi, 0, [](double, double, double) { return 1.0; });
  test::fill(*g, fields::eta, 0, [](double, double, double) { return 1.0; });
  test::fill(*g, fields::enthalpy, 0, [](double, double, double) { return 1.0; });
  test::fill(*g, fields::rho0, 0, [&](double x, double y, double z) { return a * std::exp(-(x * x + y * y + z * z) / (s * s)); });
  test::fill(*g, test::test_fluid_velocity, 1, [&](double, double, double) { return v; });
  const double exact = -1.7 * 1.7 * v / (1 - v * v) * a * std::pow(std::numbers::pi, 1.5) * s * s * s;
  CHECK(puncture::balancing_momentum(*g, fluid) == Approx(exact).epsilon(1e-8));
}

TEST_CASE("plugins.puncture.binary_hole_is_scaled_to_the_star", "[plugins][puncture]") {
  // mass_ratio = 1 beside the TOV star of rho_max = 0.1 held fixed (iterate = false, so the star is
  // settled at once and the hole keeps its start): Mhat_BH sigma = M_NS(M0) = 0.126957 for
  // M0 = 0.135313 (tov.py, physics-notes §6.1), with the sigma of the initial data (R_iso/Rhat over
  // phi_ext^2: the hole is placed again after the star's initial data), and
  // xhat_BH = -xhat_C = -0.6, a point of the grid, so moved off it by 1e-3 dx.
  test::TempDir dir;
  const auto par = dir.write("b.yaml",
                             "plugins: [grid, multigrid, eos_polytrope, tov, puncture, hamiltonian, lapse, momentum, "
                             "shift, star, flow_corotating, diagnostics]\n"
                             "grid:\n  n: 32\n  dx: 0.12\n"
                             "star:\n  rho_max: 0.1\n  x_a: 0.2\n  iterate: false\n"
                             "puncture:\n  mass_ratio: 1.0\n");
  const auto out = dir.path() / "run";
  const test::ProcessResult r = test::run_bhnsid({"run", par.string(), "--output", out.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto s = nlohmann::json::parse(test::read_file(out / "summary.json"))["scalars"];
  CHECK(s["bh_bare_mass"].get<double>() == Approx(0.126957).epsilon(2e-5));
  CHECK(s["bh_position_x_hat"].get<double>() == Approx(-0.6 + 1e-3 * 0.12).epsilon(1e-12));
  CHECK(s["bh_momentum_y"].get<double>() == 0.0);
  CHECK(test::read_file(out / "log.txt").find("lay on a grid point") != std::string::npos);
}
