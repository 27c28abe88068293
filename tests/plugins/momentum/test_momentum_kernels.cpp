// The momentum plugin's point term against eq. mom_ansatz_hat, and the manufactured solution's
// closed-form derivatives against finite differences.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <numbers>

#include "kernels.hpp"
#include "mms/problem.hpp"

using namespace bhnsid;
using Catch::Detail::Approx;

namespace {

// A 3x3x3 block of points (spacing h) laid out like a grid level: x contiguous, sy = 3, sz = 9; the
// centre is index 13, its row starts at index 12 and the centre is point i = 1 of that row.
constexpr std::ptrdiff_t sy = 3, sz = 9, centre = 13, row = 12;
constexpr double h = 0.1;

using Block = std::array<double, 27>;

template <class F>
Block sample(F&& f) {
  Block b{};
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) b[static_cast<std::size_t>(i + sy * j + sz * k)] = f(h * (i - 1), h * (j - 1), h * (k - 1));
  return b;
}

// Quadratics, whose centred first differences are exact: the gradients at the centre are the linear
// coefficients.
double wx(double x, double y, double z) { return 0.3 + 0.5 * x - 0.2 * y + 0.9 * z + 0.7 * x * y - 0.4 * z * z; }
double wy(double x, double y, double z) { return -0.1 + 0.3 * x + 0.6 * y - 0.35 * z - 0.5 * x * x + 0.2 * y * z; }
double wz(double x, double y, double z) { return 0.2 - 0.45 * x + 0.25 * y + 0.4 * z + 0.3 * x * z; }
constexpr double dw[3][3] = {{0.5, -0.2, 0.9}, {0.3, 0.6, -0.35}, {-0.45, 0.25, 0.4}};  // dw[a][j] = d_j W^a at 0
double chi_f(double x, double y, double z) { return 1.3 + 0.2 * x - 0.1 * y + 0.15 * z + 0.3 * x * x; }
double eta_f(double x, double y, double z) { return 0.7 - 0.12 * x + 0.08 * y - 0.05 * z + 0.2 * y * z; }
constexpr double dchi[3] = {0.2, -0.1, 0.15}, deta[3] = {-0.12, 0.08, -0.05};

struct Fixture {
  Block w[3] = {sample(wx), sample(wy), sample(wz)};
  Block chi = sample(chi_f), eta = sample(eta_f);
  Block pphi{}, j[3]{};  ///< j: the momentum density as the star gives it
  Fixture() {
    pphi.fill(0.4);
    j[0].fill(0.0021), j[1].fill(-0.0043), j[2].fill(0.0012);
  }
  momentum::Sources sources(double sigma, double scale) const {
    momentum::Sources s;
    s.chi = chi.data();
    s.weight = eta.data();
    s.puncture_phi = pphi.data();
    for (int c = 0; c < 3; ++c) s.matter.momentum[c] = j[c].data();
    s.sy = sy;
    s.sz = sz;
    s.inv_2h = 0.5 / h;
    s.matter.sigma2 = sigma * sigma;
    s.source_scale = scale;
    return s;
  }
  template <bool Matter>
  stencil::Triple term(const momentum::Sources& s) const {
    const momentum::MomentumLower<Matter> lower{s};
    return lower.at(centre, 1, stencil::rows_at(w[0].data() + row, sy, sz), stencil::rows_at(w[1].data() + row, sy, sz),
                    stencil::rows_at(w[2].data() + row, sy, sz));
  }
};

// The formula of physics-notes §2.1/§2.3 written out independently: N^i = -(LW)^ij (d_j eta/eta -
// 7 d_j chi/chi) - 16 pi sigma^2 eta phi^10 chi^-7 J^i.
std::array<double, 3> expected(double sigma, double scale, bool matter, const Fixture& f) {
  const double chi = chi_f(0, 0, 0), eta = eta_f(0, 0, 0), phi = 0.4 + chi;
  const double div = dw[0][0] + dw[1][1] + dw[2][2];
  std::array<double, 3> out{};
  for (int i = 0; i < 3; ++i) {
    double n = 0;
    for (int j = 0; j < 3; ++j) {
      const double lw = dw[j][i] + dw[i][j] - (i == j ? 2.0 / 3.0 * div : 0.0);
      n -= lw * (deta[j] / eta - 7.0 * dchi[j] / chi);
    }
    if (matter)
      n -= scale * 16.0 * std::numbers::pi * sigma * sigma * eta * std::pow(phi, 10) / std::pow(chi, 7) * f.j[i][centre];
    out[static_cast<std::size_t>(i)] = n;
  }
  return out;
}

void check(const stencil::Triple& t, const std::array<double, 3>& e) {
  CHECK(t.x == Approx(e[0]).epsilon(1e-12));
  CHECK(t.y == Approx(e[1]).epsilon(1e-12));
  CHECK(t.z == Approx(e[2]).epsilon(1e-12));
}

}  // namespace

TEST_CASE("plugins.momentum.point_term_is_eq_mom_ansatz_hat", "[plugins][momentum]") {
  // The lower-order term N^i of the vector operator must be -(LW)^ij (d_j eta/eta - 7 d_j chi/chi)
  // - 16 pi sigma^2 eta phi^10 chi^-7 J^i with phi = puncture_phi + chi (physics-notes §2.1, §2.3),
  // from centred differences (exact here: quadratic fields), with and without matter, and times
  // test_source_scale on the matter term only.
  Fixture f;
  const double sigma = 0.85;
  SECTION("with matter") { check(f.term<true>(f.sources(sigma, 1.0)), expected(sigma, 1.0, true, f)); }
  SECTION("vacuum") { check(f.term<false>(f.sources(sigma, 1.0)), expected(sigma, 1.0, false, f)); }
  SECTION("test_source_scale") { check(f.term<true>(f.sources(sigma, 1.03)), expected(sigma, 1.03, true, f)); }
  SECTION("the matter term is not negligible here") {
    const auto with = expected(sigma, 1.0, true, f), without = expected(sigma, 1.0, false, f);
    CHECK(std::fabs(with[1] - without[1]) > 0.1 * std::fabs(without[1]));
  }
}

TEST_CASE("plugins.momentum.point_term_ignores_w_at_the_point", "[plugins][momentum]") {
  // vector_sweep.hpp's Gauss-Seidel step assumes the point Jacobian -(20/3)/h^2: N must not read W
  // at the point itself.
  Fixture f;
  const auto before = f.term<true>(f.sources(1.0, 1.0));
  for (auto& comp : f.w) comp[centre] += 123.0;
  const auto moved = f.term<true>(f.sources(1.0, 1.0));
  CHECK(moved.x == before.x);
  CHECK(moved.y == before.y);
  CHECK(moved.z == before.z);
}

TEST_CASE("plugins.momentum.manufactured_source_matches_differences", "[plugins][momentum]") {
  // The manufactured problem's closed-form gradients and Hessians must agree with fourth-order
  // differences of its values, and its J must make W_exact satisfy eq. mom_ansatz_hat written with
  // those differences (so the convergence test's source is right); W^z must be odd in z, W^x, W^y even.
  const momentum::test::Problem p;
  const double d = 1e-3;
  using momentum::test::Vec3;
  auto shifted = [](Vec3 x, int axis, double by) {
    x[static_cast<std::size_t>(axis)] += by;
    return x;
  };
  auto diff1 = [&](auto&& f, const Vec3& x, int a) {
    return (-f(shifted(x, a, 2 * d)) + 8 * f(shifted(x, a, d)) - 8 * f(shifted(x, a, -d)) + f(shifted(x, a, -2 * d))) / (12 * d);
  };
  for (const Vec3& x : {Vec3{0.1, -0.2, 0.15}, Vec3{-0.3, 0.05, 0.3}, Vec3{0.2, 0.3, -0.1}, Vec3{0.0, 0.0, 0.0}}) {
    Vec3 op{};
    Vec3 g{};
    double div = 0;
    double grad[3][3], hess_sum[3] = {0, 0, 0}, grad_div[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a) {
      auto wa = [&](const Vec3& y) { return p.component(a, y).value; };
      const auto jet = p.component(a, x);
      for (int j = 0; j < 3; ++j) {
        grad[a][j] = diff1(wa, x, j);
        CHECK(jet.grad[static_cast<std::size_t>(j)] == Approx(grad[a][j]).margin(1e-9));
        for (int k = 0; k < 3; ++k) {
          auto dk = [&](const Vec3& y) { return p.component(a, y).grad[static_cast<std::size_t>(k)]; };
          CHECK(jet.hess[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)] == Approx(diff1(dk, x, j)).margin(1e-8));
        }
      }
      div += grad[a][a];
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        auto dwi = [&](const Vec3& y) { return p.component(i, y).grad[static_cast<std::size_t>(j)]; };
        auto dwj = [&](const Vec3& y) { return p.component(j, y).grad[static_cast<std::size_t>(j)]; };
        hess_sum[i] += diff1(dwi, x, j);
        grad_div[i] += diff1(dwj, x, i);
      }
    for (int j = 0; j < 3; ++j) {
      auto chi = [&](const Vec3& y) { return p.chi(y).value; };
      auto eta = [&](const Vec3& y) { return p.eta(y).value; };
      g[static_cast<std::size_t>(j)] = diff1(eta, x, j) / p.eta(x).value - 7 * diff1(chi, x, j) / p.chi(x).value;
    }
    for (int i = 0; i < 3; ++i) {
      double lower = 0;
      for (int j = 0; j < 3; ++j) lower += (grad[j][i] + grad[i][j] - (i == j ? 2.0 / 3.0 * div : 0.0)) * g[static_cast<std::size_t>(j)];
      op[static_cast<std::size_t>(i)] = hess_sum[i] + grad_div[i] / 3.0 - lower;
    }
    const Vec3 j = p.momentum_density(x);
    const double phi = p.puncture_phi + p.chi(x).value;
    const double factor = 16 * std::numbers::pi * p.sigma * p.sigma * p.eta(x).value * std::pow(phi, 10) / std::pow(p.chi(x).value, 7);
    for (int i = 0; i < 3; ++i) CHECK(op[static_cast<std::size_t>(i)] == Approx(factor * j[static_cast<std::size_t>(i)]).margin(1e-7));
    // The fluid carries that J: rho0 h W_L^2 V / alpha with h = 1.
    const auto fl = p.fluid(x, 0.02);
    const double alpha = p.eta(x).value / phi;
    for (int i = 0; i < 3; ++i)
      CHECK(fl.rho0 / (1 - fl.v2) * fl.velocity[static_cast<std::size_t>(i)] / alpha == Approx(j[static_cast<std::size_t>(i)]).epsilon(1e-12));
    const Vec3 mirror{x[0], x[1], -x[2]};
    CHECK(p.exact(mirror)[0] == Approx(p.exact(x)[0]));
    CHECK(p.exact(mirror)[1] == Approx(p.exact(x)[1]));
    CHECK(p.exact(mirror)[2] == Approx(-p.exact(x)[2]));
  }
}
