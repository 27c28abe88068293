// The shift plugin's point term and excision geometry, called directly (no grid plugin, no run).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "excision.hpp"
#include "kernels.hpp"
#include "test_level.hpp"
#include "support/manufactured.hpp"

using namespace bhnsid;
using namespace bhnsid::shift;
using Catch::Detail::Approx;

namespace {

using bhnsid::test::make_level;

/// A quadratic q(x) = c0 + g.x + x.H.x/2 with its exact gradient; centred differences of a
/// quadratic are exact, so the kernel's derivatives equal these to round-off.
struct Quadratic {
  double c0;
  double g[3];
  double H[3][3];
  double operator()(double x, double y, double z) const {
    const double p[3] = {x, y, z};
    double v = c0;
    for (int i = 0; i < 3; ++i) {
      v += g[i] * p[i];
      for (int j = 0; j < 3; ++j) v += 0.5 * H[i][j] * p[i] * p[j];
    }
    return v;
  }
  double d(int i, const double p[3]) const {
    double v = g[i];
    for (int j = 0; j < 3; ++j) v += H[i][j] * p[j];
    return v;
  }
};

struct PointSetup {
  Level lv = make_level(4, 0.1, false);
  std::vector<double> beta[3], chi, alpha, ahat[6], jm[3];
  Quadratic qb[3] = {{0.10, {0.3, -0.2, 0.1}, {{0.5, 0.2, -0.1}, {0.2, -0.4, 0.3}, {-0.1, 0.3, 0.6}}},
                     {-0.05, {0.1, 0.4, -0.3}, {{-0.2, 0.1, 0.0}, {0.1, 0.3, -0.2}, {0.0, -0.2, 0.1}}},
                     {0.02, {-0.25, 0.15, 0.35}, {{0.1, -0.3, 0.2}, {-0.3, 0.2, 0.1}, {0.2, 0.1, -0.5}}}};
  Quadratic qchi{1.1, {0.2, -0.1, 0.05}, {{0.3, 0.1, 0.0}, {0.1, -0.2, 0.1}, {0.0, 0.1, 0.4}}};
  Quadratic qalpha{0.8, {-0.15, 0.1, 0.2}, {{-0.2, 0.0, 0.1}, {0.0, 0.3, -0.1}, {0.1, -0.1, 0.2}}};
  // The point (i, j, k) = (2, 2, 2) at the origin, and the values there. The hole: bare mass
  // 0.6 at distance 1, so that its phi is 0.3 and its dphi -0.3 (x - xhat_BH).
  std::ptrdiff_t idx = lv.at(2, 2, 2);
  double mass = 0.6, x_bh[3] = {0.64, -0.48, 0.6};
  double a[6] = {0.2, -0.1, 0.05, 0.15, 0.3, -0.35};
  double J[3] = {0.012, -0.021, 0.0047};  // the momentum density, as the star gives it

  PointSetup() {
    auto make = [&](std::vector<double>& f) { f.assign(lv.size, 0.0); };
    for (auto& f : beta) make(f);
    for (auto* f : {&chi, &alpha}) make(*f);
    for (auto& f : ahat) make(f);
    for (auto& f : jm) make(f);
    for (int k = -1; k <= lv.nz; ++k)
      for (int j = -1; j <= lv.ny; ++j)
        for (int i = -1; i <= lv.nx; ++i) {
          const std::ptrdiff_t p = lv.at(i, j, k);
          const double x = lv.x(i), y = lv.y(j), z = lv.z(k);
          for (int c = 0; c < 3; ++c) beta[c][p] = qb[c](x, y, z);
          chi[p] = qchi(x, y, z);
          alpha[p] = qalpha(x, y, z);
        }
    for (int c = 0; c < 3; ++c) jm[c][idx] = J[c];
    for (int c = 0; c < 6; ++c) ahat[c][idx] = a[c];
  }

  Sources sources(double sigma, double scale) const {
    Sources s;
    s.chi = chi.data();
    s.alpha = alpha.data();
    s.half_mass = 0.5 * mass;
    s.x0 = lv.x(0) - x_bh[0], s.y0 = lv.y(0) - x_bh[1], s.z0 = lv.z(0) - x_bh[2];
    s.dx = lv.dx;
    for (int c = 0; c < 3; ++c) s.matter.momentum[c] = jm[c].data();
    for (int c = 0; c < 6; ++c) s.ahat[c] = ahat[c].data();
    s.matter.sigma2 = sigma * sigma;
    s.source_scale = scale;
    s.inv_2h = 0.5 / lv.dx;
    s.sy = lv.sy;
    s.sz = lv.sz;
    return s;
  }

  template <bool Hole, bool Matter>
  stencil::Triple term(double sigma, double scale) const {
    const std::ptrdiff_t p = lv.at(0, 2, 2);
    const stencil::Rows x = stencil::rows_at(beta[0].data() + p, lv.sy, lv.sz),
                        y = stencil::rows_at(beta[1].data() + p, lv.sy, lv.sz),
                        z = stencil::rows_at(beta[2].data() + p, lv.sy, lv.sz);
    return ShiftLower<Hole, Matter>{sources(sigma, scale)}.row(2, 2).at(idx, 2, x, y, z);
  }

  /// -RHS of eq. mindist_hat written out from the formula, with exact derivatives.
  std::array<double, 3> expected(bool hole, bool matter, double sigma, double scale) const {
    const double o[3] = {0, 0, 0};
    double db[3][3];  // db[i][j] = d_j beta^i
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) db[i][j] = qb[i].d(j, o);
    // The puncture's phi = Mhat/(2 r) and dphi = -Mhat (x - xhat_BH)/(2 r^3) at the origin.
    const double r = std::sqrt(x_bh[0] * x_bh[0] + x_bh[1] * x_bh[1] + x_bh[2] * x_bh[2]);
    const double punc = mass / (2 * r);
    const double phi = qchi(0, 0, 0) + (hole ? punc : 0.0);
    double dphi[3], dalpha[3];
    // alpha is the lapse service's field: the kernel differences it as it is (a quadratic: exactly).
    const double alpha = qalpha(0, 0, 0);
    for (int j = 0; j < 3; ++j) {
      dphi[j] = qchi.d(j, o) + (hole ? mass * x_bh[j] / (2 * r * r * r) : 0.0);
      dalpha[j] = qalpha.d(j, o);
    }
    const double A[3][3] = {{a[0], a[1], a[2]}, {a[1], a[3], a[4]}, {a[2], a[4], a[5]}};
    const double div = db[0][0] + db[1][1] + db[2][2];
    std::array<double, 3> n{};
    for (int i = 0; i < 3; ++i) {
      double bracket = -2.0 / 3.0 * dphi[i] * div, adal = 0;
      for (int j = 0; j < 3; ++j) bracket += (db[i][j] + db[j][i]) * dphi[j], adal += A[i][j] * dalpha[j];
      double rhs = -6 / phi * bracket + scale * 2 * std::pow(phi, -6) * adal;
      if (matter) rhs += 16 * std::numbers::pi * sigma * sigma * alpha * std::pow(phi, 4) * J[i];
      n[static_cast<std::size_t>(i)] = -rhs;
    }
    return n;
  }
};

void check_triple(const stencil::Triple& t, const std::array<double, 3>& e) {
  CHECK(t.x == Approx(e[0]).epsilon(1e-12).margin(1e-14));
  CHECK(t.y == Approx(e[1]).epsilon(1e-12).margin(1e-14));
  CHECK(t.z == Approx(e[2]).epsilon(1e-12).margin(1e-14));
}

}  // namespace

TEST_CASE("plugins.shift.point_term_is_eq_mindist_hat", "[plugins][shift]") {
  // The kernel's lower-order term is minus the right-hand side of eq. mindist_hat, with the hatted
  // dphi = puncture part + d chi, alpha (the lapse's field, differenced as it is) and the star's J^i, in all four variants
  // (hole, matter), and test_source_scale multiplies the Ahat term only.
  const PointSetup ps;
  const double sigma = 0.85;
  check_triple(ps.term<true, true>(sigma, 1.0), ps.expected(true, true, sigma, 1.0));
  check_triple(ps.term<true, false>(sigma, 1.0), ps.expected(true, false, sigma, 1.0));
  check_triple(ps.term<false, true>(sigma, 1.0), ps.expected(false, true, sigma, 1.0));
  check_triple(ps.term<false, false>(sigma, 1.0), ps.expected(false, false, sigma, 1.0));
  check_triple(ps.term<true, true>(sigma, 1.3), ps.expected(true, true, sigma, 1.3));
  // Each part is of order one here, so a wrong coefficient anywhere shows.
  const auto with = ps.expected(true, true, sigma, 1.0), without = ps.expected(true, false, sigma, 1.0);
  CHECK(std::fabs(with[0] - without[0]) > 0.01);
  const auto scaled = ps.expected(true, true, sigma, 1.3);
  CHECK(std::fabs(scaled[1] - with[1]) > 1e-3);
}

TEST_CASE("plugins.shift.point_term_stays_finite_next_to_the_hole", "[plugins][shift]") {
  // Next to the puncture phi^-1 -> 0: (6/phi) dphi ~ 6/r and phi^-6 Ahat_BY ~ r^4 stay finite down to
  // r = 1e-12, so excised points (whose residual the kernel multiplies by 0) never produce NaN.
  PointSetup ps;
  for (double r : {1e-2, 1e-6, 1e-12}) {
    ps.mass = 0.5;
    const double n[3] = {0.6, 0.8, 0};
    for (int c = 0; c < 3; ++c) ps.x_bh[c] = -r * n[c];  // the point at r n from the hole
    for (int c = 0; c < 6; ++c) ps.ahat[c][ps.idx] = ps.a[c] / (r * r);  // Bowen-York ~ P/r^2
    for (auto& j : ps.jm) j[ps.idx] = 0;
    const stencil::Triple t = ps.term<true, true>(1.0, 1.0);
    INFO("r = " << r);
    CHECK(std::isfinite(t.x));
    CHECK(std::isfinite(t.y));
    CHECK(std::isfinite(t.z));
    CHECK(std::fabs(t.x) < 100 / r);
  }
}

TEST_CASE("plugins.shift.excision_cube_has_the_documented_side", "[plugins][shift]") {
  // s = max(Mhat/2, 3 dx) (full side), points with max|x - xhat_BH| <= s/2 (+1e-12 dx) excised, and
  // the nearest interior point held on a level the cube misses.
  CHECK(excision_cube(0.2, {0, 0, 0}, 0.125).side == 0.375);
  CHECK(excision_cube(1.2, {0, 0, 0}, 0.125).side == 0.6);
  CHECK(excision_cube(0.2, {0, 0, 0}, 0.125).half == Approx(0.1875 + 1.25e-13).epsilon(1e-15));

  const Level lv = make_level(32, 0.125, true);
  std::vector<std::uint8_t> bytes(lv.size, 7);
  bool nearest = true;
  // Centre off the points: 3 points per axis in x, y and z >= 0 (z: 0 and 0.125 only, the mirror image included).
  const Cube c = excision_cube(0.2, {0.013, 0.027, 0}, 0.125);
  const int count = build_mask(lv, c, bytes.data(), nearest);
  CHECK_FALSE(nearest);
  CHECK(count == 3 * 3 * 2);
  for (int k = -1; k <= lv.nz; ++k)
    for (int j = -1; j <= lv.ny; ++j)
      for (int i = -1; i <= lv.nx; ++i) {
        const bool stored = i >= 0 && j >= 0 && k >= 0 && i < lv.nx && j < lv.ny && k < lv.nz;
        const bool in = stored && std::fabs(lv.x(i) - 0.013) <= 0.1875 && std::fabs(lv.y(j) - 0.027) <= 0.1875 &&
                        std::fabs(lv.z(k)) <= 0.1875;
        REQUIRE(bytes[static_cast<std::size_t>(lv.at(i, j, k))] == (in ? 1 : 0));
      }
  // A point exactly on the surface is inside.
  const Cube edge = excision_cube(0.2, {0.1875, 0.0, 0}, 0.125);
  build_mask(lv, edge, bytes.data(), nearest);
  CHECK(bytes[static_cast<std::size_t>(lv.at(16 + 3, 16, 0))] == 1);
  CHECK(bytes[static_cast<std::size_t>(lv.at(16 - 0, 16, 0))] == 1);
  CHECK(bytes[static_cast<std::size_t>(lv.at(16 + 4, 16, 0))] == 0);

  // A coarse level (dx = 0.5) the same cube misses: one point, the nearest to the hole.
  const Level coarse = make_level(8, 0.5, true);
  const Cube small = excision_cube(0.2, {0.26, -0.2, 0}, 0.125);
  std::vector<std::uint8_t> cb(coarse.size, 0);
  CHECK(build_mask(coarse, small, cb.data(), nearest) == 1);
  CHECK(nearest);
  CHECK(cb[static_cast<std::size_t>(coarse.at(5, 4, 0))] == 1);  // x = 0.5, y = 0
}

TEST_CASE("plugins.shift.excision_lattice_excises_one_cube_at_every_dx", "[plugins][shift]") {
  // The cube of side 0.5 about x = 0.1 has faces at -0.15 and 0.35, between the grid planes of every
  // dx = 0.15625 / 2^k on r_c = 2.5 (n = 32, 64, 128): the plain staircase holds a different region
  // at each dx. Snapped to the lattice of spacing 0.15625 through the grid's corner, the faces are
  // at -0.15625 and 0.3125 in x and -+0.3125 in y and z at every dx (nearest lattice planes), and the
  // held points are exactly the grid points of that box.
  int previous_x = 0;
  for (int n : {32, 64, 128}) {
    const double dx = 5.0 / n;
    const Level lv = make_level(n, dx, true);
    Cube plain = excision_cube(1.0, {0.1, 0, 0}, dx);
    Cube c = plain;
    snap_to_lattice(c, lv, 0.15625);
    CHECK(c.lo[0] == Approx(-0.15625).margin(1e-11));
    CHECK(c.hi[0] == Approx(0.3125).margin(1e-11));
    CHECK(c.lo[1] == Approx(-0.3125).margin(1e-11));
    CHECK(c.hi[1] == Approx(0.3125).margin(1e-11));
    CHECK(c.hi[2] == Approx(0.3125).margin(1e-11));
    std::vector<std::uint8_t> bytes(lv.size, 0);
    bool nearest = true;
    const int count = build_mask(lv, c, bytes.data(), nearest);
    const int per_x = static_cast<int>(std::lround(0.46875 / dx)) + 1, per_y = static_cast<int>(std::lround(0.625 / dx)) + 1;
    const int per_z = static_cast<int>(std::lround(0.3125 / dx)) + 1;  // z >= 0 stored
    CHECK(count == per_x * per_y * per_z);
    // The plain cube's x extent in points is not the snapped one's at every dx.
    int plain_x = 0;
    for (int i = 0; i < lv.nx; ++i) plain_x += (lv.x(i) >= plain.lo[0] && lv.x(i) <= plain.hi[0]) ? 1 : 0;
    if (previous_x > 0) CHECK(per_x - 1 == 2 * (previous_x - 1));
    previous_x = per_x;
    if (n == 32) CHECK(plain_x != per_x);
  }
}

TEST_CASE("plugins.shift.excision_value_and_outer_boundary", "[plugins][shift]") {
  // beta_0 = -v/sqrt(1 - v^2) (lorentz, the paper's form) or -v (plain) with v = Phat/Mhat signed,
  // and a cube reaching an outer face is reported.
  const auto b = excision_shift({0, -0.03, 0}, 0.2, ExcisionValue::lorentz);
  CHECK(b[0] == 0);
  CHECK(b[1] == Approx(0.15 / std::sqrt(1 - 0.0225)).epsilon(1e-14));
  CHECK(b[2] == 0);
  const auto p = excision_shift({0.01, -0.03, 0}, 0.2, ExcisionValue::plain);
  CHECK(p[0] == Approx(-0.05).epsilon(1e-14));
  CHECK(p[1] == Approx(0.15).epsilon(1e-14));

  const Level lv = make_level(32, 0.125, true);  // r_c = 2
  CHECK(cube_outside_grid(excision_cube(0.2, {1.7, 0, 0}, 0.125), lv).empty());
  CHECK_FALSE(cube_outside_grid(excision_cube(0.2, {1.83, 0, 0}, 0.125), lv).empty());
  CHECK_FALSE(cube_outside_grid(excision_cube(0.2, {0, -1.9, 0}, 0.125), lv).empty());
  CHECK_FALSE(cube_outside_grid(excision_cube(8.0, {0.013, 0, 0}, 0.125), lv).empty());  // side 4
}

TEST_CASE("plugins.shift.manufactured_current_matches_sympy", "[plugins][shift]") {
  // The momentum density that makes beta_exact exact (support/manufactured.hpp) agrees with sympy's
  // (support/manufactured_sympy.py: the formula differentiated symbolically) inside and outside R.
  struct Case {
    std::array<double, 3> x, J, beta;
  };
  const Case cases[] = {
      {{0.3, -0.4, 0.2},
       {0.0040449203057321237851, -0.0045135390460498062200, -0.0037764304622336888569},
       {0.029040715321774218750, -0.021695137147228515625, 0.012026202980400000000}},
      {{0.9, 0.7, -0.5},
       {-0.0011643777200772441781, -0.00044242230356916767629, -0.00046827970711452095463},
       {0.033128837931591094919, -0.0055643541903044070562, -0.0064516129032258064516}},
      {{-1.5, 1.2, 0.8},
       {0.000047150052552439244430, 0.000040110356736773076074, -0.00018407061435206724648},
       {0.019959805113176543855, -0.020674741366446196092, 0.0036951501154734411085}},
  };
  for (const Case& c : cases) {
    const auto J = shift::test::required_current(c.x);
    const auto b = shift::test::beta_exact(c.x);
    for (int i = 0; i < 3; ++i) {
      CHECK(J[static_cast<std::size_t>(i)] == Approx(c.J[static_cast<std::size_t>(i)]).epsilon(1e-11));
      CHECK(b[static_cast<std::size_t>(i)].v == Approx(c.beta[static_cast<std::size_t>(i)]).epsilon(1e-13));
    }
    // The fluid reproduces J at beta_exact: rho0 h W^2 (beta + V)/alpha.
    const shift::test::FluidPoint f = shift::test::fluid_exact(c.x);
    const double phi = shift::test::chi_exact(c.x).v, eta = shift::test::eta_exact(c.x).v, alpha = eta / phi;
    double U[3];
    for (int i = 0; i < 3; ++i) U[i] = b[static_cast<std::size_t>(i)].v + f.velocity[static_cast<std::size_t>(i)];
    const double w2 = 1.0 / (1.0 - std::pow(phi, 4) * (U[0] * U[0] + U[1] * U[1] + U[2] * U[2]) / (alpha * alpha));
    for (int i = 0; i < 3; ++i)
      CHECK(f.rho0 * f.enthalpy * w2 * U[i] / alpha == Approx(c.J[static_cast<std::size_t>(i)]).epsilon(1e-11));
  }
}
