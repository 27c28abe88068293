// The exact solutions and sources in closed form (problems.cpp), checked against the continuum
// equations with fine fourth-order finite differences of the exact solutions, independently of
// the grid and the kernels; and the ball's potential derived from the radial ODE.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "problems.hpp"

using namespace bhnsid::mms;

namespace {

using Field = std::function<double(const Vec3&)>;

// Fourth-order central differences with step d: error d^4 f^(6) / 90, about 1e-10 here.
double d2(const Field& f, Vec3 x, int a, double d) {
  auto at = [&](double s) {
    Vec3 y = x;
    y[static_cast<std::size_t>(a)] += s;
    return f(y);
  };
  return (-at(2 * d) + 16 * at(d) - 30 * at(0) + 16 * at(-d) - at(-2 * d)) / (12 * d * d);
}

double d1(const Field& f, Vec3 x, int a, double d) {
  auto at = [&](double s) {
    Vec3 y = x;
    y[static_cast<std::size_t>(a)] += s;
    return f(y);
  };
  return (at(-2 * d) - 8 * at(-d) + 8 * at(d) - at(2 * d)) / (12 * d);
}

double laplacian(const Field& f, const Vec3& x, double d) { return d2(f, x, 0, d) + d2(f, x, 1, d) + d2(f, x, 2, d); }

double mixed(const Field& f, const Vec3& x, int a, int b, double d) {
  if (a == b) return d2(f, x, a, d);
  return d1([&](const Vec3& y) { return d1(f, y, b, d); }, x, a, d);
}

// Deterministic points spread over the cube [-rc, rc]^3 (a fixed low-discrepancy sequence).
std::vector<Vec3> sample_points(double rc, int count) {
  std::vector<Vec3> points;
  for (int p = 1; p <= count; ++p) {
    const double a = std::fmod(p * 0.7548776662466927, 1.0), b = std::fmod(p * 0.5698402909980532, 1.0),
                 c = std::fmod(p * 0.3887, 1.0);
    points.push_back({rc * (1.8 * a - 0.9), rc * (1.8 * b - 0.9), rc * (1.8 * c - 0.9)});
  }
  return points;
}

}  // namespace

TEST_CASE("plugins.mms.poisson_is_the_peer_problem", "[plugins][mms]") {
  // On the peer's cube (r_c = 1/2, t = x + 1/2) u and s are the hypre peer's exact solution and
  // right-hand side, formulas copied from shared/peers/src/problem.hpp: u = g g g, g = t(1-t)e^t,
  // f = -(g'' g g + g g'' g + g g g''), g'' = -t(t+3)e^t. Their max u = 0.08401 at t = 0.618.
  const PoissonSolution p{0.5};
  auto g = [](double t) { return t * (1 - t) * std::exp(t); };
  auto g2 = [](double t) { return -t * (t + 3) * std::exp(t); };
  for (const Vec3& x : sample_points(0.5, 40)) {
    const double tx = x[0] + 0.5, ty = x[1] + 0.5, tz = x[2] + 0.5;
    CHECK(p.u(x) == Approx(g(tx) * g(ty) * g(tz)).epsilon(1e-14));
    CHECK(p.source(x) ==
          Approx(-(g2(tx) * g(ty) * g(tz) + g(tx) * g2(ty) * g(tz) + g(tx) * g(ty) * g2(tz))).epsilon(1e-13));
  }
  const double t = (std::sqrt(5.0) - 1) / 2;  // g' = 0: t^2 + t - 1 = 0
  CHECK(p.u({t - 0.5, t - 0.5, t - 0.5}) == Approx(0.08401).epsilon(1e-4));
  CHECK(p.u({-0.5, 0.1, 0.2}) == 0.0);
  CHECK(p.u({0.1, 0.5, 0.2}) == Approx(0.0).margin(1e-17));
}

TEST_CASE("plugins.mms.sources_solve_the_continuum_equations", "[plugins][mms]") {
  // For each problem, lap u + N(u) + s = 0 at 40 points of the cube (r_c = 1.3, an arbitrary
  // size), with lap u from fourth-order differences (step 1e-3 r_c) of the exact solution:
  // agreement to 1e-7 of the size of the terms shows every analytic source term is right.
  const double rc = 1.3, d = 1e-3 * rc;
  const auto points = sample_points(rc, 40);
  auto check = [&](double lap, double rest, double source) {
    const double scale = std::fabs(lap) + std::fabs(rest) + std::fabs(source) + 1e-3;
    CHECK(std::fabs(lap + rest + source) <= 1e-7 * scale);
  };
  SECTION("poisson") {
    const PoissonSolution p{rc};
    for (const Vec3& x : points) check(laplacian([&](const Vec3& y) { return p.u(y); }, x, d), 0.0, p.source(x));
  }
  SECTION("nonlinear") {
    for (double c : {-1.0, 0.7}) {
      const NonlinearSolution p{rc, c};
      for (const Vec3& x : points) {
        const double u = p.u(x);
        check(laplacian([&](const Vec3& y) { return p.u(y); }, x, d), c * std::pow(u, 5), p.source(x));
      }
    }
  }
  SECTION("vector") {
    for (double kappa : {0.0, 2.5}) {
      const VectorSolution p{rc, kappa};
      for (const Vec3& x : points) {
        const Vec3 v = p.v(x), s = p.source(x);
        const Vec3 n{x[0] / rc, x[1] / rc, x[2] / rc};
        const double n_dot_v = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
        for (int i = 0; i < 3; ++i) {
          auto comp = [&](int c) { return [&p, c](const Vec3& y) { return p.v(y)[static_cast<std::size_t>(c)]; }; };
          double grad_div = 0;
          for (int j = 0; j < 3; ++j) grad_div += mixed(comp(j), x, i, j, d);
          const auto a = static_cast<std::size_t>(i);
          check(laplacian(comp(i), x, d), grad_div / 3 - kappa * n[a] * n_dot_v, s[a]);
        }
      }
    }
  }
  SECTION("coupled") {
    const CoupledSolution p{rc, 1.0, -1.0};
    for (const Vec3& x : points) {
      check(laplacian([&](const Vec3& y) { return p.u(y); }, x, d), 1.0 * p.w(x), p.source_u(x));
      check(laplacian([&](const Vec3& y) { return p.w(y); }, x, d), -1.0 * std::pow(p.u(x), 3), p.source_w(x));
    }
  }
}

TEST_CASE("plugins.mms.parities_allow_equatorial_symmetry", "[plugins][mms]") {
  // Every problem allowed with equatorial symmetry is even in z, except V^z, which is odd: the
  // parities the grid gives fields of tensor kinds scalar and vector_x/y/z.
  const double rc = 1.0;
  const NonlinearSolution nl{rc, -1.0};
  const VectorSolution vec{rc, 1.5};
  const CoupledSolution cp{rc, 1.0, -1.0};
  const BallSolution ball{{0.1, 0.2, 0.0}, 1.0, 0.5};
  for (const Vec3& x : sample_points(rc, 30)) {
    const Vec3 m{x[0], x[1], -x[2]};
    CHECK(nl.u(m) == Approx(nl.u(x)).epsilon(1e-14));
    CHECK(nl.source(m) == Approx(nl.source(x)).epsilon(1e-12));
    CHECK(cp.u(m) == Approx(cp.u(x)).epsilon(1e-14));
    CHECK(cp.w(m) == Approx(cp.w(x)).epsilon(1e-14));
    CHECK(ball.u(m) == Approx(ball.u(x)).epsilon(1e-14));
    const Vec3 v = vec.v(x), vm = vec.v(m), s = vec.source(x), sm = vec.source(m);
    CHECK(vm[0] == Approx(v[0]).epsilon(1e-12));
    CHECK(vm[1] == Approx(v[1]).epsilon(1e-12));
    CHECK(vm[2] == Approx(-v[2]).epsilon(1e-12));
    CHECK(sm[0] == Approx(s[0]).epsilon(1e-12));
    CHECK(sm[1] == Approx(s[1]).epsilon(1e-12));
    CHECK(sm[2] == Approx(-s[2]).epsilon(1e-12));
  }
}

TEST_CASE("plugins.mms.ball_potential", "[plugins][mms]") {
  // The ball of mass M = 2, radius R = 0.7 at b = (0.1, -0.2, 0.05):
  //  - its density integrates to M (rho0 = 105 M / (32 pi R^3), Simpson's rule on 2000 intervals);
  //  - lap u = 4 pi rho inside and outside (fourth-order differences, step 1e-3, away from the
  //    surface where u'''' jumps);
  //  - u and u' are continuous at R (C^1, indeed C^2 since rho(R) = 0), u' = M/R^2 there, and
  //    u = -M/r outside;
  //  - radial_derivative is the derivative of radial.
  const BallSolution ball{{0.1, -0.2, 0.05}, 2.0, 0.7};
  const double M = ball.mass, R = ball.radius, pi = std::numbers::pi;

  const int intervals = 2000;
  double mass = 0;
  for (int i = 0; i <= intervals; ++i) {
    const double r = R * i / intervals;
    const double w = (i == 0 || i == intervals) ? 1 : (i % 2 ? 4 : 2);
    mass += w * 4 * pi * r * r * ball.density({ball.centre[0] + r, ball.centre[1], ball.centre[2]});
  }
  mass *= R / intervals / 3;
  CHECK(mass == Approx(M).epsilon(1e-10));

  const double d = 1e-3;
  int checked = 0;
  for (const Vec3& x : sample_points(1.2, 200)) {
    const double r = std::hypot(x[0] - ball.centre[0], x[1] - ball.centre[1], x[2] - ball.centre[2]);
    if (std::fabs(r - R) < 3 * d) continue;
    const double lap = laplacian([&](const Vec3& y) { return ball.u(y); }, x, d);
    CHECK(lap == Approx(4 * pi * ball.density(x)).margin(1e-6 * 4 * pi * ball.rho0()));
    CHECK(ball.source(x) == Approx(-4 * pi * ball.density(x)).epsilon(1e-15));
    ++checked;
  }
  CHECK(checked > 150);

  const double eps = 1e-9;
  CHECK(ball.radial(R * (1 - eps)) == Approx(ball.radial(R * (1 + eps))).epsilon(1e-8));
  CHECK(ball.radial(R) == Approx(-M / R).epsilon(1e-15));
  CHECK(ball.radial_derivative(R * (1 - eps)) == Approx(M / (R * R)).epsilon(1e-8));
  CHECK(ball.radial_derivative(R * (1 + eps)) == Approx(M / (R * R)).epsilon(1e-8));
  CHECK(ball.radial(3.0) == Approx(-M / 3.0).epsilon(1e-15));
  for (double r : {0.05, 0.3, 0.69, 0.71, 1.5}) {
    const double h = 1e-5;
    CHECK(ball.radial_derivative(r) ==
          Approx((ball.radial(r + h) - ball.radial(r - h)) / (2 * h)).epsilon(1e-8));
  }
  CHECK(ball.radial_derivative(0.0) == 0.0);
}
