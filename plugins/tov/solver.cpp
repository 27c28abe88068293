#include "solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::tov {
namespace {

constexpr double pi = std::numbers::pi;
using State = std::array<double, 4>;  // r (areal), m, M0, lambda = ln(r_iso / r) + const

// 1/sqrt(1 - x) - 1 without cancellation for small x.
double inv_sqrt_minus_one(double x) {
  const double q = std::sqrt(1.0 - x);
  return x / (q * (1.0 + q));
}

class Rhs {
 public:
  Rhs(const Eos& eos, double hc_log) : eos_(eos), hc_log_(hc_log) {}

  // d/ds of (r, m, M0, lambda) with ln h = ln h_c - s^2; needs r > 0.
  State operator()(double s, const State& y) const {
    const double r = y[0], m = y[1];
    const double h = std::exp(hc_log_ - s * s);
    const double rho0 = h > 1.0 ? eos_.rho0_from_enthalpy(h) : 0.0;
    const double p = eos_.pressure(rho0), e = eos_.energy_density(rho0);
    const double x = 2.0 * m / r;
    if (!(r > 0) || !(x < 1.0))
      throw core::RunFailure(fmt::format("TOV integration left the physical region (r = {}, 2m/r = {})", r, x));
    // dr/dH = -r (r - 2m) / (m + 4 pi r^3 P) and dH/ds = -2s.
    const double drds = 2.0 * s * r * (r - 2.0 * m) / (m + 4.0 * pi * r * r * r * p);
    const double jac = 4.0 * pi * r * r * drds;
    return {drds, jac * e, jac * rho0 / std::sqrt(1.0 - x), drds * inv_sqrt_minus_one(x) / r};
  }

 private:
  const Eos& eos_;
  double hc_log_;
};

// Dormand-Prince 5(4): returns the 5th-order step and writes the embedded error estimate.
template <class F>
State dp45_step(const F& f, double s, const State& y, double k, State& err) {
  static constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
  static constexpr double a21 = 1.0 / 5;
  static constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
  static constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
  static constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
  static constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                          a65 = -5103.0 / 18656;
  static constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84;
  static constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                          e6 = 22.0 / 525, e7 = -1.0 / 40;
  auto add = [&](std::initializer_list<std::pair<double, const State*>> terms) {
    State out = y;
    for (const auto& [c, kv] : terms)
      for (std::size_t i = 0; i < out.size(); ++i) out[i] += k * c * (*kv)[i];
    return out;
  };
  const State k1 = f(s, y);
  const State k2 = f(s + c2 * k, add({{a21, &k1}}));
  const State k3 = f(s + c3 * k, add({{a31, &k1}, {a32, &k2}}));
  const State k4 = f(s + c4 * k, add({{a41, &k1}, {a42, &k2}, {a43, &k3}}));
  const State k5 = f(s + c5 * k, add({{a51, &k1}, {a52, &k2}, {a53, &k3}, {a54, &k4}}));
  const State k6 = f(s + k, add({{a61, &k1}, {a62, &k2}, {a63, &k3}, {a64, &k4}, {a65, &k5}}));
  const State y5 = add({{b1, &k1}, {b3, &k3}, {b4, &k4}, {b5, &k5}, {b6, &k6}});
  const State k7 = f(s + k, y5);
  for (std::size_t i = 0; i < err.size(); ++i)
    err[i] = k * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
  return y5;
}

struct Point {
  double s;
  State y;
};

}  // namespace

double isotropic_radius_of(double m, double r) { return 0.5 * (r - m + std::sqrt(r * r - 2.0 * m * r)); }
double exterior_psi(double m, double r_iso) { return 1.0 + m / (2.0 * r_iso); }
double exterior_lapse(double m, double r_iso) { return (1.0 - m / (2.0 * r_iso)) / (1.0 + m / (2.0 * r_iso)); }

TovStar solve_star(const Eos& eos, double rho_c, const Settings& settings, Stats* stats) {
  if (!(rho_c > 0) || !std::isfinite(rho_c))
    throw core::RunFailure(fmt::format("TOV: central density {} is not positive", rho_c));
  const double hc = eos.enthalpy(rho_c);
  if (!(hc > 1.0) || !std::isfinite(hc))
    throw core::RunFailure(fmt::format("TOV: h(rho_c = {}) = {} (EOS {}): no star", rho_c, hc, eos.describe()));
  const double hc_log = std::log(hc), s_surf = std::sqrt(hc_log);
  const double pc = eos.pressure(rho_c), ec = eos.energy_density(rho_c);

  // Series start at s0 << s_surf: ln h_c - ln h = (2 pi / 3)(e_c + 3 P_c) r^2 + O(r^4),
  // m = (4 pi / 3) e_c r^3, M0 = (4 pi / 3) rho_c r^3, lambda = (2 pi / 3) e_c r^2 (from
  // d lambda / dr = (1/sqrt(1 - 2m/r) - 1)/r = m/r^2 + ...); relative errors O(r0^2), which enter the
  // results as O(r0^4) (the perturbation of r decays like r0 / r).
  const double s0 = 1e-5 * s_surf;
  const double r0 = s0 / std::sqrt(2.0 * pi / 3.0 * (ec + 3.0 * pc));
  const double v0 = 4.0 * pi / 3.0 * r0 * r0 * r0;
  std::vector<Point> points{{0.0, {0.0, 0.0, 0.0, 0.0}}, {s0, {r0, v0 * ec, v0 * rho_c, 2.0 * pi / 3.0 * ec * r0 * r0}}};

  const Rhs f(eos, hc_log);
  const double max_step = s_surf / std::max(1, settings.min_steps);
  Stats st;
  double s = s0;
  State y = points.back().y, err{};
  // Adaptive Dormand-Prince 5(4) from s to s_end, appending the accepted points.
  auto adaptive = [&](double s_end, double tol) {
    double k = std::min(max_step, s0);
    while (s < s_end) {
      const bool last = s + k >= s_end * (1 - 1e-14);
      if (last) k = s_end - s;
      const State yn = dp45_step(f, s, y, k, err);
      double e = 0;
      for (std::size_t i = 0; i < y.size(); ++i) {
        // lambda starts near 0: measure it against 2m/r, its natural size, as well.
        const double scale = std::max(std::fabs(y[i]), std::fabs(yn[i])) + (i == 3 ? 2.0 * yn[1] / yn[0] : 0.0);
        e = std::max(e, std::fabs(err[i]) / (tol * scale + 1e-300));
      }
      if (!std::isfinite(e)) throw core::RunFailure(fmt::format("TOV: non-finite error at s = {} (rho_c = {})", s, rho_c));
      if (e <= 1.0) {
        s = last ? s_end : s + k;
        y = yn;
        points.push_back({s, y});
        ++st.accepted;
      } else {
        ++st.rejected;
      }
      k = std::min(max_step, k * std::clamp(0.9 * std::pow(std::max(e, 1e-30), -0.2), 0.2, 5.0));
      if (k < 1e-14 * s_surf || st.accepted + st.rejected > 10'000'000)
        throw core::RunFailure(fmt::format("TOV: step size collapsed at s = {} (rho_c = {})", s, rho_c));
    }
  };
  if (settings.fixed_steps > 0) {
    // Fixed steps in t with s = s_surf sinh(B t) / sinh(B), sinh(B) = s_surf / s0, from the series
    // start t0 (s = s0) to t = 1: near the centre the steps are geometric in s (ds/s ~ B dt), which
    // the scale-free behaviour there (r ~ s, the right-hand side ~ s/r) needs for the full order;
    // near the surface ds ~ B s_surf dt.
    const double big_b = std::asinh(s_surf / s0), sinh_b = std::sinh(big_b);
    const double t0 = std::asinh(s0 * sinh_b / s_surf) / big_b;
    struct Mapped {
      const Rhs& f;
      double s_surf, b, sinh_b;
      double s_of(double t) const { return s_surf * std::sinh(b * t) / sinh_b; }
      State operator()(double t, const State& y) const {
        State d = f(s_of(t), y);
        const double dsdt = s_surf * b * std::cosh(b * t) / sinh_b;
        for (double& v : d) v *= dsdt;
        return d;
      }
    } g{f, s_surf, big_b, sinh_b};
    const double k = (1.0 - t0) / settings.fixed_steps;
    for (int i = 1; i <= settings.fixed_steps; ++i) {
      const double t = t0 + (i - 1) * k;
      y = dp45_step(g, t, y, k, err);
      s = i == settings.fixed_steps ? s_surf : g.s_of(t0 + i * k);
      points.push_back({s, y});
      ++st.accepted;
    }
  } else {
    adaptive(s_surf, settings.tolerance);
  }
  if (stats) *stats = st;

  TovStar star;
  star.central_density = rho_c;
  const double R = y[0], M = y[1];
  star.adm_mass = M;
  star.rest_mass = y[2];
  star.radius_areal = R;
  star.radius_isotropic = isotropic_radius_of(M, R);
  // lambda = ln(r_iso / r) + shift, matched to the exterior at the surface.
  const double shift = std::log(star.radius_isotropic / R) - y[3];
  const double alpha_surface = std::sqrt(1.0 - 2.0 * M / R);
  for (const Point& p : points) {
    const double h = std::exp(hc_log - p.s * p.s);
    const double lambda = p.y[3] + shift;
    star.r_areal.push_back(p.y[0]);
    star.r_iso.push_back(p.y[0] * std::exp(lambda));
    star.psi.push_back(std::exp(-0.5 * lambda));  // psi = sqrt(r / r_iso)
    star.alpha.push_back(alpha_surface / h);       // alpha h = const (hydrostatic equilibrium)
    star.rho0.push_back(p.s >= s_surf ? 0.0 : (p.s == 0 ? rho_c : eos.rho0_from_enthalpy(h)));
  }
  star.r_iso.back() = star.radius_isotropic;
  star.psi.back() = std::sqrt(R / star.radius_isotropic);
  star.alpha.back() = alpha_surface;
  star.lapse_center = star.alpha.front();
  star.psi_center = star.psi.front();
  return star;
}

std::string profile_table(const TovStar& star, int exterior_points, double outer_factor) {
  std::string out = "# r_iso\tr_areal\tpsi\talpha\trho0\n";
  for (std::size_t i = 0; i < star.r_iso.size(); ++i)
    out += fmt::format("{:.17g}\t{:.17g}\t{:.17g}\t{:.17g}\t{:.17g}\n", star.r_iso[i], star.r_areal[i], star.psi[i],
                       star.alpha[i], star.rho0[i]);
  const double M = star.adm_mass, r1 = star.radius_isotropic;
  for (int i = 1; i <= exterior_points; ++i) {
    const double ri = r1 * (1.0 + (outer_factor - 1.0) * i / exterior_points);
    const double psi = exterior_psi(M, ri);
    out += fmt::format("{:.17g}\t{:.17g}\t{:.17g}\t{:.17g}\t0\n", ri, ri * psi * psi, psi, exterior_lapse(M, ri));
  }
  return out;
}

}  // namespace bhnsid::tov
