// The (sigma, Omegahat, C_B) Newton solve of the star (physics-notes §4.4) on a synthetic model with a
// known root, with the corotating first integral written out here.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "outer_newton.hpp"

using namespace bhnsid::star;
using Catch::Detail::Approx;

namespace {

// Fields whose model changes are alpha_P: -b_P (s - s0) - e (s - s0)^2, phi_P: d_P (s - s0), and point
// values chosen so that (sigma*, Omega*, C*) solves every F_P.
struct Synthetic {
  double s0 = 2.0, s_star = 1.93, w_star = 0.071, c_star = 0.84;
  double x[3] = {1.0, 0.45, 0.73}, beta[3] = {0.004, 0.011, 0.007}, h[3] = {1.0, 1.0, 1.19};
  double b[3] = {0.031, 0.052, 0.094}, d[3] = {0.012, 0.02, 0.035}, p[3] = {1.03, 1.07, 1.06};
  double e = 0;       // curvature of the lapse model (e > 0: Newton from below overshoots)
  double fold = 1e9;  // the model has no solution above this sigma
  mutable double highest_trial = 0;

  std::vector<AxisPoint> points() const {
    std::vector<AxisPoint> out(3);
    for (int i = 0; i < 3; ++i) {
      const double ph = p[i] + d[i] * (s_star - s0), u = beta[i] + x[i] * w_star;
      const double a_star = std::sqrt(c_star * c_star / (h[i] * h[i]) + std::pow(ph, 4) * u * u);
      const double shift = b[i] * (s_star - s0) + e * (s_star - s0) * (s_star - s0);
      out[static_cast<std::size_t>(i)] = {0.0, a_star + shift, p[i], h[i]};
    }
    return out;
  }
  /// The corotating residual F = h^2 (alpha^2 - phi^4 (beta^y + x Omega)^2) - C^2 (physics-notes §4.4).
  PointResidual residual() const {
    return [this](std::size_t i, double a, double ph, double w, double c, double hh) {
      const double u = beta[i] + x[i] * w, ph4 = std::pow(ph, 4);
      return bhnsid::AxisResidual{hh * hh * (a * a - ph4 * u * u) - c * c, -2 * hh * hh * ph4 * u * x[i], -2 * c};
    };
  }
  FieldModel model() const {
    return [this](double s) {
      highest_trial = std::max(highest_trial, s);
      if (s > fold) throw bhnsid::core::RunFailure("above the fold");
      ModelValues m;
      for (int i = 0; i < 3; ++i) {
        m.alpha.push_back(0.7 - b[i] * (s - s0) - e * (s - s0) * (s - s0));
        m.phi.push_back(1.1 + d[i] * (s - s0));
      }
      return m;
    };
  }
};

}  // namespace

TEST_CASE("plugins.star.orbit_newton_finds_the_root", "[plugins][star]") {
  const Synthetic syn;
  const NewtonResult r = solve_sigma_omega_bernoulli(syn.points(), syn.model(), syn.residual(), syn.s0, 0.05, 0.85);
  CHECK(r.sigma == Approx(syn.s_star).epsilon(1e-10));
  CHECK(r.omega_hat == Approx(syn.w_star).epsilon(1e-9));
  CHECK(r.bernoulli == Approx(syn.c_star).epsilon(1e-10));
  CHECK(r.iterations < 15);
}

TEST_CASE("plugins.star.orbit_newton_backtracks_at_the_fold", "[plugins][star]") {
  // A curved lapse model and a start far below the root: the first full step goes to sigma = 1.99,
  // past a fold just above the root (1.95); it is halved until the model has a solution, and the
  // root is still found.
  Synthetic syn;
  syn.s0 = 1.6;
  syn.e = 0.3;
  syn.fold = 1.95;
  const NewtonResult r = solve_sigma_omega_bernoulli(syn.points(), syn.model(), syn.residual(), syn.s0, 0.02, 0.9);
  CHECK(syn.highest_trial > syn.fold);
  CHECK(r.sigma == Approx(syn.s_star).epsilon(1e-10));
  CHECK(r.omega_hat == Approx(syn.w_star).epsilon(1e-9));
}

TEST_CASE("plugins.star.orbit_newton_refuses_what_it_cannot_solve", "[plugins][star]") {
  const Synthetic syn;
  // Omegahat must start > 0 (the root with the star moving in +y), and three points are needed.
  CHECK_THROWS_AS(solve_sigma_omega_bernoulli(syn.points(), syn.model(), syn.residual(), syn.s0, 0.0, 0.85), bhnsid::core::RunFailure);
  std::vector<AxisPoint> two = syn.points();
  two.pop_back();
  CHECK_THROWS_AS(solve_sigma_omega_bernoulli(two, syn.model(), syn.residual(), syn.s0, 0.05, 0.85), bhnsid::core::RunFailure);
  // A fold below every sigma the iteration can reach: a clear failure, never a silent answer.
  Synthetic low = syn;
  low.fold = 1.0;
  CHECK_THROWS_AS(solve_sigma_omega_bernoulli(low.points(), low.model(), low.residual(), 2.0, 0.05, 0.85), bhnsid::core::RunFailure);
}
