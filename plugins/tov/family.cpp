#include "family.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::tov {

Family::Family(const Eos& eos, Settings settings, SearchSettings search, FrozenSettings frozen)
    : eos_(eos), settings_(settings), search_(search), frozen_settings_(frozen) {}

TovStar Family::star(double central_density) const { return solve_star(eos_, central_density, settings_); }

// Log scan for the largest mass, then golden-section search in ln rho_c on the bracket around it.
double Family::maximize(bool rest_mass) const {
  auto mass = [&](double log_rho) {
    const TovStar s = star(std::exp(log_rho));
    return rest_mass ? s.rest_mass : s.adm_mass;
  };
  const int n = std::max(3, search_.scan_points);
  const double a0 = std::log(search_.density_min), a1 = std::log(search_.density_max);
  std::vector<double> x(static_cast<std::size_t>(n)), v(x.size());
  std::size_t best = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = a0 + (a1 - a0) * static_cast<double>(i) / (n - 1);
    v[i] = mass(x[i]);
    if (v[i] > v[best]) best = i;
  }
  if (best == 0 || best + 1 == x.size())
    throw core::RunFailure(fmt::format(
        "TOV: the {} mass has no maximum inside the central densities [{}, {}] (EOS {}); widen tov.search_density_*",
        rest_mass ? "rest" : "ADM", search_.density_min, search_.density_max, eos_.describe()));
  double lo = x[best - 1], hi = x[best + 1];
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = hi - g * (hi - lo), d = lo + g * (hi - lo);
  double fc = mass(c), fd = mass(d);
  while (hi - lo > search_.relative_tolerance) {
    if (fc > fd) {
      hi = d, d = c, fd = fc;
      c = hi - g * (hi - lo), fc = mass(c);
    } else {
      lo = c, c = d, fc = fd;
      d = lo + g * (hi - lo), fd = mass(d);
    }
  }
  return std::exp(0.5 * (lo + hi));
}

TovStar Family::maximum_mass_star() const {
  std::lock_guard lock(mutex_);
  if (!max_adm_) max_adm_ = star(maximize(false));
  return *max_adm_;
}

TovStar Family::maximum_rest_mass_star() const {
  std::lock_guard lock(mutex_);
  if (!max_rest_) max_rest_ = star(maximize(true));
  return *max_rest_;
}

double Family::central_density_from_rest_mass(double m0) const {
  const TovStar top = maximum_rest_mass_star();
  if (!(m0 > 0) || m0 > top.rest_mass)
    throw core::RunFailure(fmt::format("TOV: no stable star of rest mass {} (EOS {}: 0 < M0 <= (M0)_max = {:.9g})", m0,
                                       eos_.describe(), top.rest_mass));
  if (m0 == top.rest_mass) return top.central_density;
  double hi = top.central_density, lo = 0.5 * hi;
  for (int i = 0; star(lo).rest_mass >= m0; ++i, lo *= 0.5)
    if (i > 200) throw core::RunFailure(fmt::format("TOV: cannot bracket the star of rest mass {}", m0));
  // Regula falsi (Illinois) in ln rho_c: M0 increases monotonically with rho_c on the stable branch,
  // so the bracket holds; the binary asks for M_NS(M0) every outer iteration, and bisection to
  // 1e-14 took 46 TOV solves (11% of the paper example's run at n = 64), this about 8.
  double a = std::log(lo), b = std::log(hi);
  double fa = star(lo).rest_mass - m0, fb = top.rest_mass - m0;
  // M0 itself carries round-off of about 1e-13 relative (the profile's integration): a bracket of
  // 1e-12 in ln rho_c is as far as the function can guide it.
  int side = 0;
  for (int i = 0; i < 200; ++i) {
    if (b - a <= 1e-12) return std::exp(0.5 * (a + b));
    const double c = fb == fa ? 0.5 * (a + b) : b - fb * (b - a) / (fb - fa);
    const double mid = std::clamp(c, a + 0.01 * (b - a), b - 0.01 * (b - a));  // never stall at an end
    const double fm = star(std::exp(mid)).rest_mass - m0;
    if (fm == 0 || std::fabs(fm) <= 1e-14 * m0) return std::exp(mid);
    if ((fm < 0) == (fa < 0)) {
      a = mid, fa = fm;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = mid, fb = fm;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  throw core::RunFailure(fmt::format("TOV: the central density of the star of rest mass {} did not converge", m0));
}

TovStar Family::star_from_rest_mass(double m0) const { return star(central_density_from_rest_mass(m0)); }

double Family::adm_mass_from_rest_mass(double m0) const { return star_from_rest_mass(m0).adm_mass; }

FrozenProfileSolution Family::frozen_profile(double rho_max, double rhat_star, double sigma) const {
  if (!(rho_max > 0) || !std::isfinite(rho_max) || !(rhat_star > 0) || !std::isfinite(rhat_star))
    throw core::RunFailure(fmt::format("TOV: frozen-profile model needs rho_max > 0 and rhat_star > 0, not {} and {}",
                                       rho_max, rhat_star));
  std::lock_guard lock(frozen_mutex_);
  const auto key = std::make_pair(rho_max, rhat_star);
  auto it = frozen_.find(key);
  if (it == frozen_.end()) {
    if (frozen_.size() >= 8) frozen_.erase(frozen_.begin());
    it = frozen_.emplace(key, make_frozen(rho_max, rhat_star)).first;
  }
  return it->second->solve(sigma);
}

std::unique_ptr<FrozenProfileModel> Family::make_frozen(double rho_max, double rhat_star) const {
  // The source is interpolated from the profile: 2048 steps put that error near 1e-12 (256: 1e-10);
  // the tighter tolerance keeps the profile consistent to ~1e-11 across the kinks of a piecewise
  // EOS, where 1e-12 leaves ~1e-9 (SLy). A few ms, once per model.
  Settings dense = settings_;
  dense.min_steps = std::max(dense.min_steps, 2048);
  dense.tolerance = std::min(dense.tolerance, 1e-14);
  const TovStar frozen = solve_star(eos_, rho_max, dense);
  return std::make_unique<FrozenProfileModel>(eos_, frozen, rhat_star, frozen_settings_);
}

}  // namespace bhnsid::tov
