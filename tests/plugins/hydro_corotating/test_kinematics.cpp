// The corotating fluid's matter projections (what every field equation reads) against the
// stress-energy tensor built from the 4-metric, and the StarFluid service on a grid.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>

#include "fluid.hpp"
#include "grid_fill.hpp"
#include "real_grid.hpp"
#include "kinematics.hpp"
#include "test_fluid.hpp"

using namespace bhnsid;
using namespace bhnsid::hydro_corotating;
using Catch::Detail::Approx;

namespace {

using Mat4 = std::array<std::array<double, 4>, 4>;

/// The inverse of a 4x4 matrix by Gauss-Jordan elimination with partial pivoting.
Mat4 inverse(Mat4 a) {
  Mat4 inv{};
  for (int i = 0; i < 4; ++i) inv[i][i] = 1;
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    std::swap(a[c], a[p]);
    std::swap(inv[c], inv[p]);
    const double d = a[c][c];
    for (int k = 0; k < 4; ++k) a[c][k] /= d, inv[c][k] /= d;
    for (int r = 0; r < 4; ++r)
      if (r != c) {
        const double f = a[r][c];
        for (int k = 0; k < 4; ++k) a[r][k] -= f * a[c][k], inv[r][k] -= f * inv[c][k];
      }
  }
  return inv;
}

}  // namespace

TEST_CASE("plugins.hydro_corotating.projections_are_those_of_the_stress_tensor", "[plugins][hydro_corotating]") {
  // From the 4-metric ds^2 = -alpha^2 dt^2 + phi^4 (dx + beta dt)^2 and the corotating 4-velocity
  // u = u^t (1, Omega xi) normalised by g(u, u) = -1, T^ab = rho0 h u^a u^b + P g^ab gives
  // rho_E = n_a n_b T^ab, j^i = -gamma^i_a T^ab n_b, S = gamma_ab T^ab with n_a = (-alpha, 0, 0, 0)
  // (physics-notes §1.2). The plugin's closed forms must agree to round-off.
  const double phi = 1.13, eta = 0.81, omega = 0.21, rho0 = 0.07, press = rho0 * rho0, h = 1 + 2 * rho0;
  const double x = 0.9, y = -0.35;  // V = Omega xi does not depend on z
  const double beta[3] = {0.013, -0.041, 0.006};
  const double alpha = eta / phi, psi4 = std::pow(phi, 4);
  const double V[3] = {-omega * y, omega * x, 0.0};
  Mat4 g{};
  double beta_low[3], b2 = 0;
  for (int i = 0; i < 3; ++i) beta_low[i] = psi4 * beta[i], b2 += beta_low[i] * beta[i];
  g[0][0] = -alpha * alpha + b2;
  for (int i = 0; i < 3; ++i) {
    g[0][i + 1] = g[i + 1][0] = beta_low[i];
    g[i + 1][i + 1] = psi4;
  }
  double u[4] = {1, V[0], V[1], V[2]}, norm = 0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) norm += g[a][b] * u[a] * u[b];
  REQUIRE(norm < 0);
  for (double& c : u) c /= std::sqrt(-norm);
  const Mat4 ginv = inverse(g);
  Mat4 T{};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) T[a][b] = rho0 * h * u[a] * u[b] + press * ginv[a][b];
  const double rho_e = alpha * alpha * T[0][0];
  // T^a_b n^b... j^i = -gamma^i_a T^ab n_b = alpha gamma^i_a T^a0, gamma^i_a = delta^i_a + n^i n_a,
  // n^i = -beta^i/alpha, n_0 = -alpha: gamma^i_0 = beta^i, gamma^i_j = delta^i_j.
  double j[3], s = 0;
  for (int i = 0; i < 3; ++i) j[i] = alpha * (T[i + 1][0] + beta[i] * T[0][0]);
  // S = gamma_ab T^ab with gamma_ab = g_ab + n_a n_b.
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) s += (g[a][b] + (a == 0 && b == 0 ? alpha * alpha : 0.0)) * T[a][b];

  const double ux = beta[0] + V[0], uy = beta[1] + V[1], uz = beta[2] + V[2];
  const double w2 = lorentz_squared(phi, alpha, ux, uy, uz);
  const Projections p = projections(rho0, press, h, w2, alpha, ux, uy, uz);
  CHECK(p.energy == Approx(rho_e).epsilon(1e-12));
  CHECK(p.trace == Approx(s).epsilon(1e-12));
  CHECK(p.jx == Approx(j[0]).epsilon(1e-12));
  CHECK(p.jy == Approx(j[1]).epsilon(1e-12));
  CHECK(p.jz == Approx(j[2]).epsilon(1e-12));
  // W = alpha u^t.
  CHECK(std::sqrt(w2) == Approx(alpha * u[0]).epsilon(1e-12));
}

TEST_CASE("plugins.hydro_corotating.no_lorentz_factor_where_the_lapse_is_not_positive", "[plugins][hydro_corotating]") {
  // Inside the hole's horizon a singular lapse is <= 0 on solved points: no observer corotates there,
  // so W is NaN (never a finite value of the wrong sign), for either sign of alpha and at rest too.
  for (const double alpha : {0.0, -1e-3, -0.4})
    for (const double u : {0.0, 1e-3}) {
      INFO("alpha = " << alpha << ", u = " << u);
      CHECK(std::isnan(lorentz_squared(1.2, alpha, u, 0.0, 0.0)));
    }
  CHECK(lorentz_squared(1.2, 0.4, 0.0, 0.0, 0.0) == 1.0);
}

namespace {

std::unique_ptr<grid::UniformGrid> make_grid(int n, double dx) {
  return test::equatorial_grid(n, dx, {fields::chi, fields::eta, fields::puncture_phi, fields::alpha});
}

}  // namespace

TEST_CASE("plugins.hydro_corotating.rest_mass_of_a_gaussian", "[plugins][hydro_corotating]") {
  // phi = 1, at rest (W = 1): M0 = sigma^3 Int rho0 = sigma^3 a pi^(3/2) s^3 (trapezoid rule, smooth
  // decayed integrand: far below 1e-8 at n = 32).
  auto g = make_grid(32, 0.125);
  StarFluid fluid;
  const test::EtaOverPhiLapse lapse;
  fluid.attach(*g, lapse);
  fluid.constants.sigma = 1.3;
  const double a = 0.02, s = 0.4;
  test::fill(*g, fields::chi, 0, [](double, double, double) { return 1.0; });
  test::fill(*g, fields::eta, 0, [](double, double, double) { return 1.0; });
  test::fill(*g, fields::rho0, 0, [&](double x, double y, double z) { return a * std::exp(-(x * x + y * y + z * z) / (s * s)); });
  CHECK(fluid.rest_mass() == Approx(std::pow(1.3, 3) * a * std::pow(std::numbers::pi, 1.5) * s * s * s).epsilon(1e-8));
}

TEST_CASE("plugins.hydro_corotating.projections_vanish_outside_the_matter", "[plugins][hydro_corotating]") {
  // Omegahat = 1 makes the corotating velocity superluminal beyond r ~ 1 (W is NaN there); outside
  // the star (rho0 = 0) every projection must be exactly 0, inside finite and as at one point.
  auto g = make_grid(16, 0.25);
  StarFluid fluid;
  const test::EtaOverPhiLapse lapse;
  fluid.attach(*g, lapse);
  fluid.constants.sigma = 1;
  fluid.constants.omega_hat = 1;
  test::fill(*g, fields::chi, 0, [](double, double, double) { return 1.0; });
  test::fill(*g, fields::eta, 0, [](double, double, double) { return 1.0; });
  test::fill(*g, fields::rho0, 0, [](double x, double y, double z) { return std::hypot(x, y, z) < 0.5 ? 0.05 : 0.0; });
  test::fill(*g, fields::press, 0, [](double x, double y, double z) { return std::hypot(x, y, z) < 0.5 ? 0.0025 : 0.0; });
  test::fill(*g, fields::enthalpy, 0, [](double x, double y, double z) { return std::hypot(x, y, z) < 0.5 ? 1.1 : 1.0; });
  fluid.update_sources(*g, 0);
  const Level& lv = g->finest();
  const int e = g->field_id(fields::matter_energy), j = g->field_id(fields::matter_momentum);
  int inside = 0;
  for (int k = 0; k < lv.nz; ++k)
    for (int jj = 0; jj < lv.ny; ++jj)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, jj, k);
        const double x = lv.x(i), y = lv.y(jj), r = std::hypot(x, y, lv.z(k));
        const double energy = g->data(e, 0, 0)[p], jy = g->data(j, 1, 0)[p];
        if (r >= 0.5) {
          REQUIRE(energy == 0.0);
          REQUIRE(jy == 0.0);
          continue;
        }
        ++inside;
        const double w2 = 1.0 / (1.0 - (x * x + y * y));
        REQUIRE(energy == Approx(0.05 * 1.1 * w2 - 0.0025).epsilon(1e-13));
        REQUIRE(jy == Approx(0.05 * 1.1 * w2 * x).epsilon(1e-13).margin(1e-15));
      }
  CHECK(inside > 10);
}
