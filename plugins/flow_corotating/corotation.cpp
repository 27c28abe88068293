#include "corotation.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "kinematics.hpp"

namespace bhnsid::flow_corotating {

namespace {

/// The level's arrays the kinematics read; beta is null without a shift equation (beta = 0).
struct Inputs {
  const double *rho0, *press, *enthalpy, *chi, *alpha, *puncture_phi;
  const double* beta[3] = {nullptr, nullptr, nullptr};
};

/// Refreshes alpha on `level` from the lapse and gathers the arrays.
Inputs inputs(Grid& grid, const Lapse& lapse, int level) {
  Inputs in{grid.data(grid.field_id(fields::rho0), 0, level),     grid.data(grid.field_id(fields::press), 0, level),
            grid.data(grid.field_id(fields::enthalpy), 0, level), grid.data(grid.field_id(fields::chi), 0, level),
            lapse_on(grid, lapse, level),                         grid.data(grid.field_id(fields::puncture_phi), 0, level)};
  if (grid.has_field(fields::shift)) {
    const int beta = grid.field_id(fields::shift);
    for (int c = 0; c < 3; ++c) in.beta[c] = grid.data(beta, c, level);
  }
  return in;
}

/// Calls fn(p, ux, uy, uz, lorentz2, alpha, phi) per stored point, U = beta + Omegahat xi. The
/// matter is selected where rho0 > 0 by the callers (not branched on), so that the rows vectorise.
template <bool Shift, class Fn>
void for_points(const Level& lv, const Inputs& in, double omega_hat, Fn&& fn) {
  for_stored_points_xy(lv, [&](std::ptrdiff_t p, double x, double y) {
    double ux = -omega_hat * y, uy = omega_hat * x, uz = 0.0;
    if constexpr (Shift) {
      ux += in.beta[0][p];
      uy += in.beta[1][p];
      uz += in.beta[2][p];
    }
    const double phi = in.puncture_phi[p] + in.chi[p];
    const double w2 = lorentz_squared(phi, in.alpha[p], ux, uy, uz);
    fn(p, ux, uy, uz, w2, in.alpha[p], phi);
  });
}

template <class Fn>
void for_points(const Level& lv, const Inputs& in, double omega_hat, Fn&& fn) {
  if (in.beta[0])
    for_points<true>(lv, in, omega_hat, fn);
  else
    for_points<false>(lv, in, omega_hat, fn);
}

}  // namespace

const Lapse& Corotation::lapse() const {
  if (!lapse_) throw core::RunFailure("flow_corotating: used before SETUP gave it the lapse");
  return *lapse_;
}

void Corotation::update_sources(Grid& grid, int level, const FlowConstants& c) const {
  const Level& lv = grid.level(level);
  const Inputs in = inputs(grid, lapse(), level);
  double* energy = grid.data(grid.field_id(fields::matter_energy), 0, level);
  double* trace = grid.data(grid.field_id(fields::matter_trace), 0, level);
  const int mom = grid.field_id(fields::matter_momentum);
  double* j[3] = {grid.data(mom, 0, level), grid.data(mom, 1, level), grid.data(mom, 2, level)};
  for_points(lv, in, c.omega_hat, [&](std::ptrdiff_t p, double ux, double uy, double uz, double w2, double alpha, double) {
    const double rho0 = in.rho0[p];
    const Projections m = projections(rho0, in.press[p], in.enthalpy[p], w2, alpha, ux, uy, uz);
    // Outside the star W may be NaN (U superluminal far out); the select drops it.
    const bool matter = rho0 > 0;
    energy[p] = matter ? m.energy : 0.0;
    trace[p] = matter ? m.trace : 0.0;
    j[0][p] = matter ? m.jx : 0.0;
    j[1][p] = matter ? m.jy : 0.0;
    j[2][p] = matter ? m.jz : 0.0;
  });
}

void Corotation::velocity(Grid& grid, const FlowConstants& c, double* lorentz, double* const* v) const {
  const Inputs in = inputs(grid, lapse(), 0);
  for_points(grid.finest(), in, c.omega_hat,
             [&](std::ptrdiff_t p, double ux, double uy, double uz, double w2, double alpha, double) {
               const bool matter = in.rho0[p] > 0;
               lorentz[p] = matter ? std::sqrt(w2) : 1.0;
               if (v) {
                 const double inv_alpha = 1.0 / alpha;
                 v[0][p] = matter ? ux * inv_alpha : 0.0;
                 v[1][p] = matter ? uy * inv_alpha : 0.0;
                 v[2][p] = matter ? uz * inv_alpha : 0.0;
               }
             });
}

std::string Corotation::acausal_matter(Grid& grid, const FlowConstants& c) const {
  const Level& lv = grid.finest();
  const Inputs in = inputs(grid, lapse(), 0);
  // Only asked after a failure: the scalar search costs nothing.
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        if (!(in.rho0[p] > 0)) continue;
        const double u[3] = {-c.omega_hat * lv.y(j) + (in.beta[0] ? in.beta[0][p] : 0.0),
                             c.omega_hat * lv.x(i) + (in.beta[1] ? in.beta[1][p] : 0.0), in.beta[2] ? in.beta[2][p] : 0.0};
        const double phi = in.puncture_phi[p] + in.chi[p];
        if (std::isfinite(lorentz_squared(phi, in.alpha[p], u[0], u[1], u[2]))) continue;
        return fmt::format("|beta + Omegahat xi| phi^2 / alpha = {:.4g} at ({:.4g}, {:.4g}, {:.4g}), alpha = {:.4g}",
                           phi * phi * std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) / in.alpha[p], lv.x(i), lv.y(j),
                           lv.z(k), in.alpha[p]);
      }
  return {};
}

void Corotation::enthalpy(Grid& grid, const FlowConstants& c, const double* alpha, const double* phi, double* h) const {
  const Level& lv = grid.finest();
  const double* beta[3] = {nullptr, nullptr, nullptr};
  if (grid.has_field(fields::shift))
    for (int k = 0; k < 3; ++k) beta[k] = grid.data(grid.field_id(fields::shift), k, 0);
  const double w = c.omega_hat;
  // h from h sqrt(alpha^2 - phi^4 |beta + Omegahat xi|^2) = C_B (eq. bernoulli_hat); an argument <= 0
  // (near the hole, beyond the light cylinder) is marked h = -1.
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        const double a = alpha[p], ph2 = phi[p] * phi[p];
        double u2 = 0;
        const double v[3] = {-w * lv.y(j), w * lv.x(i), 0.0};
        for (int q = 0; q < 3; ++q) {
          const double u = v[q] + (beta[q] ? beta[q][p] : 0.0);
          u2 += u * u;
        }
        const double arg = a * a - ph2 * ph2 * u2;
        h[p] = a > 0 && arg > 0 ? c.bernoulli / std::sqrt(arg) : -1.0;
      }
}

void Corotation::first_integral(Grid& grid, const FlowConstants& c, double* out) const {
  const Inputs in = inputs(grid, lapse(), 0);
  for_points(grid.finest(), in, c.omega_hat, [&](std::ptrdiff_t p, double, double, double, double w2, double alpha, double) {
    // h / u^t = h alpha / W.
    out[p] = in.rho0[p] > 0 ? in.enthalpy[p] * alpha / std::sqrt(w2) : std::numeric_limits<double>::quiet_NaN();
  });
}

void Corotation::freeze_axis(Grid& grid, const std::vector<double>& xs, const FlowConstants&) {
  axis_x_ = xs;
  axis_beta_y_.assign(xs.size(), 0.0);
  if (!grid.has_field(fields::shift)) return;
  const double* beta_y = grid.data(grid.field_id(fields::shift), 1, 0);
  for (std::size_t p = 0; p < xs.size(); ++p)
    axis_beta_y_[p] = grid.interpolate(beta_y, Parity{}, 0, {xs[p], 0, 0});
}

AxisResidual Corotation::axis_residual(std::size_t p, double alpha, double phi, double omega_hat, double bernoulli,
                                       double enthalpy) const {
  // F_P = h_P^2 [alpha_P^2 - phi_P^4 (beta^y_P + xhat_P Omegahat)^2] - C_B^2 (physics-notes §4.4).
  const double h2 = enthalpy * enthalpy, ph2 = phi * phi, x = axis_x_.at(p);
  const double u = axis_beta_y_.at(p) + x * omega_hat;
  return {h2 * (alpha * alpha - ph2 * ph2 * u * u) - bernoulli * bernoulli, -2.0 * h2 * ph2 * ph2 * u * x, -2.0 * bernoulli};
}

}  // namespace bhnsid::flow_corotating
