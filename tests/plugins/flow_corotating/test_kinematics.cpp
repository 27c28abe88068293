// The corotating flow's matter projections (what every field equation reads) against the
// stress-energy tensor built from the 4-metric, and the Corotation flow on a grid: its projections,
// velocity and first integral.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>

#include "corotation.hpp"
#include "grid_fill.hpp"
#include "real_grid.hpp"
#include "kinematics.hpp"
#include "test_fluid.hpp"

using namespace bhnsid;
using namespace bhnsid::flow_corotating;
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

TEST_CASE("plugins.flow_corotating.projections_are_those_of_the_stress_tensor", "[plugins][flow_corotating]") {
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

TEST_CASE("plugins.flow_corotating.no_lorentz_factor_where_the_lapse_is_not_positive", "[plugins][flow_corotating]") {
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

/// A grid with the fields a flow reads and writes (the star registers them in a run).
std::unique_ptr<grid::UniformGrid> make_grid(int n, double dx) {
  auto g = test::equatorial_grid(n, dx,
                                 {fields::chi, fields::eta, fields::puncture_phi, fields::alpha, fields::rho0, fields::press,
                                  fields::enthalpy, fields::matter_energy, fields::matter_trace});
  static_cast<Grid&>(*g).add_field(fields::matter_momentum,
                                   {core::TensorKind::vector_x, core::TensorKind::vector_y, core::TensorKind::vector_z},
                                   core::TimeParity::odd);
  return g;
}

}  // namespace

TEST_CASE("plugins.flow_corotating.projections_vanish_outside_the_matter", "[plugins][flow_corotating]") {
  // Omegahat = 1 makes the corotating velocity superluminal beyond r ~ 1 (W is NaN there); outside
  // the star (rho0 = 0) every projection must be exactly 0, inside finite and as at one point.
  auto g = make_grid(16, 0.25);
  Corotation flow;
  const test::EtaOverPhiLapse lapse;
  flow.attach(lapse);
  test::fill(*g, fields::chi, 0, [](double, double, double) { return 1.0; });
  test::fill(*g, fields::eta, 0, [](double, double, double) { return 1.0; });
  test::fill(*g, fields::rho0, 0, [](double x, double y, double z) { return std::hypot(x, y, z) < 0.5 ? 0.05 : 0.0; });
  test::fill(*g, fields::press, 0, [](double x, double y, double z) { return std::hypot(x, y, z) < 0.5 ? 0.0025 : 0.0; });
  test::fill(*g, fields::enthalpy, 0, [](double x, double y, double z) { return std::hypot(x, y, z) < 0.5 ? 1.1 : 1.0; });
  flow.update_sources(*g, 0, {1.0, 1.0, 0.9});
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

TEST_CASE("plugins.flow_corotating.first_integral_inverts_the_enthalpy", "[plugins][flow_corotating]") {
  // h = C_B / sqrt(alpha^2 - phi^4 |beta + Omega xi|^2) from enthalpy(), then h alpha / W from
  // first_integral() with those h: C_B back at every matter point; W and v from velocity() are those
  // of the kinematics (v = (beta + Omega xi)/alpha), and -1 marks the points beyond the light cylinder.
  auto g = make_grid(16, 0.25);
  Corotation flow;
  const test::EtaOverPhiLapse lapse;
  flow.attach(lapse);
  const FlowConstants c{1.0, 0.5, 0.87};
  test::fill(*g, fields::chi, 0, [](double x, double, double) { return 1.05 + 0.02 * x; });
  test::fill(*g, fields::eta, 0, [](double, double y, double) { return 0.9 - 0.01 * y; });
  const Level& lv = g->finest();
  const double* alpha = lapse_on(*g, lapse, 0);
  std::vector<double> phi(lv.size, 1.0), h(lv.size, 0.0), integral(lv.size, 0.0), lorentz(lv.size, 0.0);
  const double* chi = g->data(g->field_id(fields::chi), 0, 0);
  for_stored_points(lv, [&](std::ptrdiff_t p) { phi[p] = chi[p]; });
  flow.enthalpy(*g, c, alpha, phi.data(), h.data());
  double* rho0 = g->data(g->field_id(fields::rho0), 0, 0);
  double* enthalpy = g->data(g->field_id(fields::enthalpy), 0, 0);
  int matter = 0, outside = 0;
  for_stored_points(lv, [&](std::ptrdiff_t p) {
    rho0[p] = h[p] > 0 ? 0.01 : 0.0;
    enthalpy[p] = h[p] > 0 ? h[p] : 1.0;
  });
  flow.first_integral(*g, c, integral.data());
  std::vector<double> v[3] = {std::vector<double>(lv.size), std::vector<double>(lv.size), std::vector<double>(lv.size)};
  double* vp[3] = {v[0].data(), v[1].data(), v[2].data()};
  flow.velocity(*g, c, lorentz.data(), vp);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        if (!(h[p] > 0)) {
          ++outside;
          REQUIRE(h[p] == -1.0);
          REQUIRE(std::isnan(integral[p]));
          continue;
        }
        ++matter;
        REQUIRE(integral[p] == Approx(c.bernoulli).epsilon(1e-13));
        REQUIRE(v[1][p] == Approx(c.omega_hat * lv.x(i) / alpha[p]).epsilon(1e-13).margin(1e-15));
        REQUIRE(lorentz[p] == Approx(std::sqrt(lorentz_squared(phi[p], alpha[p], -c.omega_hat * lv.y(j),
                                                               c.omega_hat * lv.x(i), 0.0))).epsilon(1e-13));
      }
  CHECK(matter > 100);
  CHECK(outside > 100);  // |Omega xi| phi^2 reaches alpha within the cube at Omegahat = 0.5
}

TEST_CASE("plugins.flow_corotating.axis_residual_is_the_corotating_bernoulli_equation", "[plugins][flow_corotating]") {
  // F = h^2 (alpha^2 - phi^4 (beta^y + x Omega)^2) - C^2 with its Omegahat and C_B derivatives against
  // central differences; beta = 0 without a shift field.
  auto g = make_grid(8, 0.25);
  Corotation flow;
  flow.freeze_axis(*g, {1.0, 0.3}, {1.0, 0.2, 0.8});
  const double a = 0.8, ph = 1.1, w = 0.2, c = 0.8, h = 1.07, e = 1e-6;
  const AxisResidual r = flow.axis_residual(0, a, ph, w, c, h);
  CHECK(r.f == Approx(h * h * (a * a - std::pow(ph, 4) * w * w) - c * c).epsilon(1e-14));
  CHECK(r.df_domega == Approx((flow.axis_residual(0, a, ph, w + e, c, h).f - flow.axis_residual(0, a, ph, w - e, c, h).f) /
                              (2 * e)).epsilon(1e-7));
  CHECK(r.df_dbernoulli == Approx(-2 * c).epsilon(1e-14));
  CHECK(flow.axis_residual(1, a, ph, w, c, h).f == Approx(h * h * (a * a - std::pow(ph, 4) * 0.09 * w * w) - c * c).epsilon(1e-14));
}
