#include "frozen_profile.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::tov {
namespace {

constexpr double pi = std::numbers::pi;
constexpr std::size_t max_cached = 32;  // continuation starting points kept besides sigma_tov
constexpr int max_newton = 40;
constexpr double newton_tolerance = 1e-13;  // on max |delta phi|, phi ~ 1
constexpr double min_relative_step = 1e-9;  // below this the failed continuation is a fold

// 8-point Gauss-Legendre on [-1, 1] (positive half; the rule is symmetric).
constexpr std::array<double, 4> gl_x{0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                     0.9602898564975363};
constexpr std::array<double, 4> gl_w{0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                     0.1012285362903763};

// Quadratic Lagrange basis on the nodes t = -h, 0, h.
std::array<double, 3> lagrange3(double t, double h) {
  const double h2 = h * h;
  return {t * (t - h) / (2 * h2), (h2 - t * t) / h2, t * (t + h) / (2 * h2)};
}

}  // namespace

FrozenProfileModel::FrozenProfileModel(const Eos& eos, const TovStar& star, double rhat_star,
                                       FrozenSettings settings)
    : settings_(settings),
      rho_max_(star.central_density),
      rhat_star_(rhat_star),
      sigma_tov_(star.radius_isotropic / rhat_star),
      n_(std::max(8, settings.points)),
      h_(rhat_star / n_) {
  if (!(rhat_star > 0) || !std::isfinite(rhat_star))
    throw core::RunFailure(fmt::format("tov: frozen-profile model needs rhat_star > 0, not {}", rhat_star));
  if (!(settings_.step > 0)) settings_.step = 0.005;
  r_.resize(static_cast<std::size_t>(n_) + 1);
  for (int i = 0; i <= n_; ++i) r_[static_cast<std::size_t>(i)] = rhat_star * i / n_;
  // The profile with strictly increasing r_iso; the enthalpy h = alpha_surface / alpha is smooth in
  // r_iso through the EOS piece boundaries, so rho0, e and P follow from it exactly.
  Profile prof;
  for (std::size_t j = 0; j < star.r_iso.size(); ++j)
    if (prof.r_iso.empty() || star.r_iso[j] > prof.r_iso.back()) {
      prof.r_iso.push_back(star.r_iso[j]);
      prof.enthalpy.push_back(star.alpha.back() / star.alpha[j]);
      prof.psi.push_back(star.psi[j]);
    }
  if (prof.r_iso.size() < 4) throw core::RunFailure(fmt::format("tov: {}: TOV profile too short", describe()));
  compute_weights(eos, prof, star.radius_isotropic);

  // Newton from the exact TOV conformal factor gives the discrete solution at sigma_tov.
  std::vector<double> phi(r_.size());
  const double to_iso = star.radius_isotropic / rhat_star;
  for (std::size_t i = 0; i < r_.size(); ++i)
    phi[i] = detail::interpolate_cubic(prof.r_iso, prof.psi, std::min(r_[i] * to_iso, star.radius_isotropic), true);
  int sign = 0;
  if (!newton(sigma_tov_, phi, sign) || sign == 0)
    throw core::RunFailure(fmt::format("tov: {}: Newton failed at sigma_tov from the TOV star", describe()));
  det_sign_ = sign;
  cache_[sigma_tov_] = Entry{std::move(phi), std::nullopt};
}

std::string FrozenProfileModel::describe() const {
  return fmt::format("frozen-profile model (physics-notes 4.5) of rho_max = {}, rhat_star = {}, sigma_tov = {:.12g}",
                     rho_max_, rhat_star_, sigma_tov_);
}

// Product integration: every row is an exact integral identity of (r u)'' = r S(r) with the smooth
// factor phi^5 (or phi^4 eta) interpolated quadratically between the nodes and the frozen density,
// which has kinks (surface, EOS pieces), integrated by Gauss-Legendre per cell. Fourth order.
void FrozenProfileModel::compute_weights(const Eos& eos, const Profile& prof, double radius_iso) {
  const double to_iso = radius_iso / rhat_star_;
  auto sample = [&](double rhat, double weight) {
    QPoint p{rhat, weight, 0.0, 0.0};
    const double ri = rhat * to_iso;
    if (ri >= radius_iso) return p;
    const double h = detail::interpolate_cubic(prof.r_iso, prof.enthalpy, ri, true);
    const double rho0 = h > 1 ? eos.rho0_from_enthalpy(h) : 0.0;
    if (!(rho0 > 0)) return p;
    p.e = eos.energy_density(rho0);
    p.e2s = p.e + 6.0 * eos.pressure(rho0);  // S = 3P for a static fluid
    return p;
  };
  auto gauss = [&](double a, double b) {
    std::vector<QPoint> pts;
    for (std::size_t g = 0; g < 8; ++g) {
      const std::size_t m = g < 4 ? 3 - g : g - 4;
      const double xi = g < 4 ? -gl_x[m] : gl_x[m];
      pts.push_back(sample(a + 0.5 * (b - a) * (1.0 + xi), 0.5 * (b - a) * gl_w[m]));
    }
    return pts;
  };
  auto moment = [](const std::vector<QPoint>& pts) {
    double sum = 0;
    for (const QPoint& p : pts) sum += p.w * p.e * p.s * p.s;
    return sum;
  };
  // The EOS piece boundaries and the crust-core junction are kinks of e(r): an 8-point rule on a cell
  // with a kink is only O(h^3) accurate, and erratically so (it depends on where the kink falls).
  // Halve the cells where the two halves disagree with the whole. The tolerance stays 1e3 above the
  // rounding of the sums (and the EOS's rounding-level jumps between pieces): a tighter one would
  // refine noise without end. The depth and the point budget bound the work in any case.
  const double scale = eos.energy_density(rho_max_) * rhat_star_ * rhat_star_;
  std::vector<QPoint> points;
  auto refine = [&](auto&& self, double a, double b, const std::vector<QPoint>& whole, int depth) -> void {
    const double m = 0.5 * (a + b);
    std::vector<QPoint> left = gauss(a, m), right = gauss(m, b);
    const double diff = std::fabs(moment(left) + moment(right) - moment(whole));
    if (depth >= 30 || points.size() > 4096 || diff <= 1e-13 * scale * (b - a)) {
      points.insert(points.end(), left.begin(), left.end());
      points.insert(points.end(), right.begin(), right.end());
      return;
    }
    self(self, a, m, left, depth + 1);
    self(self, m, b, right, depth + 1);
  };

  const std::size_t n = static_cast<std::size_t>(n_);
  w_e_.assign(n + 1, {0, 0, 0});
  w_s_.assign(n + 1, {0, 0, 0});
  const double h = h_;
  for (std::size_t j = 0; j < n; ++j) {  // cell [r_j, r_j+1]
    points.clear();
    refine(refine, r_[j], r_[j + 1], gauss(r_[j], r_[j + 1]), 0);
    for (const QPoint& p : points) {
      if (p.e == 0 && p.e2s == 0) continue;
      const double s = p.s;
      auto add = [&](std::size_t row, const std::array<double, 3>& basis, double kernel) {
        for (std::size_t k = 0; k < 3; ++k) {
          w_e_[row][k] += p.w * kernel * p.e * basis[k];
          w_s_[row][k] += p.w * kernel * p.e2s * basis[k];
        }
      };
      if (j == 0) {
        // Centre: u1 - u0 = Int_0^h s (1 - s/h) S ds, the factor even in s: q0 (1 - s^2/h^2) + q1 s^2/h^2.
        const double y = s * s / (h * h);
        add(0, {0.0, 1.0 - y, y}, s * (1.0 - s / h));
      }
      // Interior rows i = j (right half-cell) and i = j + 1 (left half-cell):
      // r_{i+1} u_{i+1} - 2 r_i u_i + r_{i-1} u_{i-1} = Int_{-h}^{h} (h - |t|) (r_i + t) S dt.
      if (j >= 1) add(j, lagrange3(s - r_[j], h), (h - (s - r_[j])) * s);
      if (j + 1 <= n - 1) add(j + 1, lagrange3(s - r_[j + 1], h), (h + (s - r_[j + 1])) * s);
      if (j == n - 1) {
        // Surface row: r_N u_N - r_{N-1} u_{N-1} = h (r u)'(R) - Int_{r_{N-1}}^{R} (s - r_{N-1}) s S ds,
        // and (r u)' = 1 there is the Robin condition, exact outside the matter (u = 1 + c/r).
        add(n, lagrange3(s - r_[n - 1], h), (s - r_[n - 1]) * s);
      }
    }
  }
}

// Rows with the unknowns' linear part and c x (weights . dq): the Jacobian of the phi equation
// (dq = 5 phi^4, c = -2 pi sigma^2) or the matrix of the eta equation (dq = phi^4, c = 2 pi sigma^2).
void FrozenProfileModel::assemble(double c, const Weights& w, const std::vector<double>& dq, Band& b) const {
  const std::size_t n = static_cast<std::size_t>(n_);
  b.lo.assign(n + 1, 0.0);
  b.di.assign(n + 1, 0.0);
  b.up.assign(n + 1, 0.0);
  b.di[0] = -1.0 - c * w[0][1] * dq[0];
  b.up[0] = 1.0 - c * w[0][2] * dq[1];
  for (std::size_t i = 1; i < n; ++i) {
    b.lo[i] = r_[i - 1] - c * w[i][0] * dq[i - 1];
    b.di[i] = -2.0 * r_[i] - c * w[i][1] * dq[i];
    b.up[i] = r_[i + 1] - c * w[i][2] * dq[i + 1];
  }
  b.extra = c * w[n][0] * dq[n - 2];
  b.lo[n] = -r_[n - 1] + c * w[n][1] * dq[n - 1];
  b.di[n] = r_[n] + c * w[n][2] * dq[n];
}

int FrozenProfileModel::solve_band(Band b, std::vector<double>& x) {
  const std::size_t n = b.di.size() - 1;
  int sign = 1;
  // Forward elimination; row k becomes x_k + up_k x_{k+1} = x_k (rhs). The (N, N-2) entry of the
  // last row is removed with the reduced row N-2 first (a row operation: the determinant is kept).
  for (std::size_t i = 0; i <= n; ++i) {
    if (i == n) {
      b.lo[n] -= b.extra * b.up[n - 2];
      x[n] -= b.extra * x[n - 2];
    }
    const double piv = i == 0 ? b.di[0] : b.di[i] - b.lo[i] * b.up[i - 1];
    if (!(std::fabs(piv) > 0) || !std::isfinite(piv)) return 0;
    if (piv < 0) sign = -sign;
    x[i] = (i == 0 ? x[0] : x[i] - b.lo[i] * x[i - 1]) / piv;
    b.up[i] = i == n ? 0.0 : b.up[i] / piv;
  }
  for (std::size_t i = n; i-- > 0;) x[i] -= b.up[i] * x[i + 1];
  return sign;
}

bool FrozenProfileModel::newton(double sigma, std::vector<double>& u, int& det_sign) {
  const std::size_t n = static_cast<std::size_t>(n_);
  const double c = -2.0 * pi * sigma * sigma;
  std::vector<double> q(n + 1), dq(n + 1), f(n + 1);
  Band band;
  double previous = std::numeric_limits<double>::infinity();
  for (int it = 0; it < max_newton; ++it) {
    ++last_iterations_;
    for (std::size_t i = 0; i <= n; ++i) {
      const double u2 = u[i] * u[i], u4 = u2 * u2;
      q[i] = u4 * u[i];
      dq[i] = 5.0 * u4;
    }
    f[0] = u[1] - u[0] - c * (w_e_[0][1] * q[0] + w_e_[0][2] * q[1]);
    for (std::size_t i = 1; i < n; ++i)
      f[i] = r_[i + 1] * u[i + 1] - 2.0 * r_[i] * u[i] + r_[i - 1] * u[i - 1] -
             c * (w_e_[i][0] * q[i - 1] + w_e_[i][1] * q[i] + w_e_[i][2] * q[i + 1]);
    f[n] = r_[n] * u[n] - r_[n - 1] * u[n - 1] - h_ +
           c * (w_e_[n][0] * q[n - 2] + w_e_[n][1] * q[n - 1] + w_e_[n][2] * q[n]);
    assemble(c, w_e_, dq, band);
    for (double& v : f) v = -v;
    det_sign = solve_band(band, f);
    if (det_sign == 0) return false;
    double change = 0;
    for (std::size_t i = 0; i <= n; ++i) {
      u[i] += f[i];
      if (!(u[i] > 0) || !std::isfinite(u[i])) return false;
      change = std::max(change, std::fabs(f[i]));
    }
    // Converged, or stalled at the rounding level after quadratic convergence.
    if (change < newton_tolerance || (change < 1e-10 && change > 0.25 * previous)) return true;
    previous = change;
  }
  return false;
}

FrozenProfileSolution FrozenProfileModel::finish(double sigma, const std::vector<double>& phi) const {
  const std::size_t n = static_cast<std::size_t>(n_);
  std::vector<double> p4(n + 1), eta(n + 1, 0.0);
  for (std::size_t i = 0; i <= n; ++i) p4[i] = std::pow(phi[i], 4);
  Band band;
  assemble(2.0 * pi * sigma * sigma, w_s_, p4, band);
  eta[n] = h_;  // the only inhomogeneous row: the Robin condition (r eta)' = 1
  if (solve_band(band, eta) == 0)
    throw core::RunFailure(fmt::format("tov: {}: singular lapse system at sigma = {}", describe(), sigma));
  FrozenProfileSolution s;
  s.sigma = sigma;
  s.sigma_tov = sigma_tov_;
  s.rhat = r_;
  s.phi = phi;
  s.alpha.resize(n + 1);
  for (std::size_t i = 0; i <= n; ++i) {
    if (!(eta[i] > 0) || !std::isfinite(eta[i]))
      throw core::RunFailure(
          fmt::format("tov: {}: eta = {} at rhat = {} (sigma = {})", describe(), eta[i], r_[i], sigma));
    s.alpha[i] = eta[i] / phi[i];
  }
  return s;
}

void FrozenProfileModel::remember(double sigma, std::vector<double> phi, std::optional<FrozenProfileSolution> full) {
  if (cache_.count(sigma)) return;
  cache_[sigma] = Entry{std::move(phi), std::move(full)};
  order_.push_back(sigma);
  if (order_.size() > max_cached) {
    cache_.erase(order_.front());
    order_.pop_front();
  }
}

FrozenProfileSolution FrozenProfileModel::solve(double sigma) {
  last_iterations_ = 0;
  if (!(sigma > 0) || !std::isfinite(sigma))
    throw core::RunFailure(fmt::format("tov: {}: sigma = {} is not positive", describe(), sigma));
  auto fold_error = [&](double at) {
    const double below = fold_lower_.value_or(sigma_tov_);
    return core::RunFailure(fmt::format(
        "tov: {}: no solution at sigma = {:.12g} ({:.6f} sigma_tov): it is above the fold of the spherical "
        "Hamiltonian constraint with a fixed source, sigma_fold ~ {:.12g} ({:.6f} sigma_tov; continuation failed at "
        "{:.12g}). Keep sigma below the fold (physics-notes 2.2, fold guard of 4.4).",
        describe(), sigma, sigma / sigma_tov_, below, below / sigma_tov_, at));
  };
  if (no_solution_from_ && sigma >= *no_solution_from_) throw fold_error(*no_solution_from_);
  if (auto hit = cache_.find(sigma); hit != cache_.end()) {
    if (!hit->second.full) hit->second.full = finish(sigma, hit->second.phi);
    return *hit->second.full;
  }
  // Continue from the nearest known solution (all lie on the branch of the TOV star).
  auto next = cache_.lower_bound(sigma);
  auto start = next;
  if (next == cache_.end() || (next != cache_.begin() && sigma - std::prev(next)->first < next->first - sigma))
    start = std::prev(next);
  double s = start->first;
  std::vector<double> u = start->second.phi;
  const double dir = sigma > s ? 1.0 : -1.0;
  double k = settings_.step * s;
  while (s != sigma) {
    const double target = std::fabs(sigma - s) <= k ? sigma : s + dir * k;
    std::vector<double> trial = u;
    int sign = 0;
    if (newton(target, trial, sign) && sign == det_sign_) {
      s = target;
      u = std::move(trial);
      k = std::min(2.0 * k, settings_.step * s);
      continue;
    }
    // A sign change of the Jacobian means the step jumped to the other branch: also a failure.
    k *= 0.5;
    if (k < min_relative_step * s) {
      if (dir > 0) {
        fold_lower_ = std::max(fold_lower_.value_or(s), s);
        no_solution_from_ = std::min(no_solution_from_.value_or(target), target);
        throw fold_error(target);
      }
      throw core::RunFailure(fmt::format("tov: {}: continuation from sigma = {:.12g} down to {:.12g} failed at {:.12g}",
                                         describe(), start->first, sigma, target));
    }
  }
  FrozenProfileSolution out = finish(sigma, u);
  remember(sigma, std::move(u), out);
  return out;
}

}  // namespace bhnsid::tov
