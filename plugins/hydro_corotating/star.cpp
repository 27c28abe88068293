#include "star.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "outer_newton.hpp"
#include "tov_profile.hpp"

namespace bhnsid::hydro_corotating {

using core::RunFailure;

Star::Star(Grid& grid, const Eos& eos, const TovFamily& family, StarSettings settings, std::shared_ptr<StarFluid> fluid)
    : grid_(grid), eos_(eos), family_(family), settings_(settings), fluid_(std::move(fluid)) {
  const std::vector<core::TensorKind> scalar{core::TensorKind::scalar};
  rho0_ = grid.add_field(fields::rho0, scalar);
  press_ = grid.add_field(fields::press, scalar);
  enthalpy_ = grid.add_field(fields::enthalpy, scalar);
  chi_ = grid.field_id(fields::chi);
  eta_ = grid.field_id(fields::eta);
  puncture_phi_ = grid.field_id(fields::puncture_phi);
  tov_ = family.star(settings.rho_max);
  fluid_->constants.x_c = 0.5 * (1.0 + settings.x_a);
  fluid_->robin_centre = fluid_->constants.x_c;
  fluid_->constants.sigma = settings.sigma_guess > 0 ? settings.sigma_guess : tov_.radius_isotropic / rhat_star();
  fluid_->constants.bernoulli = eos.enthalpy(settings.rho_max) * tov_.lapse_center;
}

void Star::set_initial() {
  const Level& lv = grid_.finest();
  // The TOV star placed on hatted radius Rhat whatever the initial sigma (physics-notes §4.7): a
  // sigma_guess away from R_iso/Rhat then starts from the same density with other field constants.
  const double scale = tov_.radius_isotropic / rhat_star(), x_c = fluid_->constants.x_c;
  double* rho0 = grid_.data(rho0_, 0, 0);
  double* chi = grid_.data(chi_, 0, 0);
  double* eta = grid_.data(eta_, 0, 0);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        const TovPoint t = tov_at(tov_, scale * std::hypot(lv.x(i) - x_c, lv.y(j), lv.z(k)));
        rho0[p] = t.rho0;
        chi[p] = t.psi;
        eta[p] = t.alpha * t.psi;
      }
  for (int f : {chi_, eta_}) grid_.fill_ghosts(f, 0);
  fill_thermodynamics();
}

void Star::fill_thermodynamics() {
  const Level& lv = grid_.finest();
  const double* rho0 = grid_.data(rho0_, 0, 0);
  double* press = grid_.data(press_, 0, 0);
  double* enthalpy = grid_.data(enthalpy_, 0, 0);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        press[p] = eos_.pressure(rho0[p]);
        enthalpy[p] = eos_.enthalpy(rho0[p]);
      }
  for (int f : {rho0_, press_, enthalpy_}) grid_.fill_ghosts(f, 0);
}

namespace {

/// alpha = eta / phi on the finest level, ghosts filled, for interpolation.
std::vector<double> lapse_field(Grid& grid, int chi, int eta, int puncture_phi) {
  const Level& lv = grid.finest();
  std::vector<double> alpha(lv.size, 1.0);
  const double* c = grid.data(chi, 0, 0);
  const double* e = grid.data(eta, 0, 0);
  const double* b = grid.data(puncture_phi, 0, 0);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        alpha[p] = e[p] / (b[p] + c[p]);
      }
  grid.fill_ghosts(alpha.data(), Parity{}, 0);
  return alpha;
}

}  // namespace

StepReport Star::step() {
  StepReport report;
  report.iteration = static_cast<int>(history_.size()) + 1;
  StarConstants& now = fluid_->constants;
  report.before = now;
  report.after = now;
  if (!settings_.iterate) {
    report.converged = true;
    history_.push_back(report);
    return report;
  }
  const std::vector<double> alpha = lapse_field(grid_, chi_, eta_, puncture_phi_);
  const double rhat = rhat_star();
  // The centre (h = h_max) and the surface point xhat = 1 (h = 1); for a static star xhat_A is
  // equivalent to xhat = 1 by symmetry, so two points fix (sigma, C_B) (physics-notes §9 T1).
  std::vector<AxisPoint> points(2);
  points[0] = {0.0, grid_.interpolate(alpha.data(), Parity{}, 0, {now.x_c, 0, 0}), eos_.enthalpy(settings_.rho_max)};
  points[1] = {1.0 - now.x_c, grid_.interpolate(alpha.data(), Parity{}, 0, {1.0, 0, 0}), 1.0};
  const AlphaModel model = [&](double s) {
    const FrozenProfileSolution m = family_.frozen_profile(settings_.rho_max, rhat, s);
    return std::vector<double>{m.alpha_at(points[0].rhat), m.alpha_at(points[1].rhat)};
  };
  const NewtonResult solved = solve_sigma_bernoulli(points, model, now.sigma);
  report.after.sigma = solved.sigma;
  report.after.bernoulli = solved.bernoulli;
  report.change = std::max(std::fabs(solved.sigma / now.sigma - 1), std::fabs(solved.bernoulli / now.bernoulli - 1));
  // Converged: keep the density the fields were just solved with, so the output is consistent;
  // the Bernoulli equation then holds to about the tolerance (physics-notes §4.2).
  if (report.change < settings_.tolerance && report.iteration > 1) {
    report.converged = true;
    report.after = now;
    report.matter_points = -1;
    history_.push_back(report);
    return report;
  }
  report.matter_points = bernoulli_reset(report.after);
  now.sigma = report.after.sigma;
  now.bernoulli = report.after.bernoulli;
  now.x_c = axis_maximum();
  report.after = now;
  history_.push_back(report);
  return report;
}

int Star::bernoulli_reset(const StarConstants& next) {
  const Level& lv = grid_.finest();
  const StarConstants& now = fluid_->constants;
  const double rhat = rhat_star();
  const FrozenProfileSolution model_new = family_.frozen_profile(settings_.rho_max, rhat, next.sigma);
  const FrozenProfileSolution model_old = family_.frozen_profile(settings_.rho_max, rhat, now.sigma);
  const std::vector<double> alpha = lapse_field(grid_, chi_, eta_, puncture_phi_);
  // Enthalpy from h alpha~ = C_B with the sigma-modelled lapse (§4.8); 0 where there is no matter.
  std::vector<double> h(lv.size, 0.0);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        const double r = std::hypot(lv.x(i) - now.x_c, lv.y(j), lv.z(k));
        const double a = alpha[p] + model_new.alpha_at(r) - model_old.alpha_at(r);
        h[p] = a > 0 ? next.bernoulli / a : 0.0;
      }
  // The star is the 6-connected component of {h > 1} containing the point nearest xhat_C (§3).
  const int i0 = static_cast<int>(std::lround((now.x_c - lv.origin[0]) / lv.dx));
  const int j0 = lv.n / 2, k0 = lv.z_symmetry ? 0 : lv.n / 2;
  if (!(h[lv.at(i0, j0, k0)] > 1))
    throw RunFailure(fmt::format("hydro_corotating: the Bernoulli reset leaves no matter at the centre xhat_C = {} "
                                 "(h = {} there, sigma = {}, C_B = {})",
                                 now.x_c, h[lv.at(i0, j0, k0)], next.sigma, next.bernoulli));
  std::vector<std::uint8_t> in_star(lv.size, 0);
  std::vector<std::array<int, 3>> todo{{i0, j0, k0}};
  in_star[lv.at(i0, j0, k0)] = 1;
  int count = 0;
  while (!todo.empty()) {
    const auto [i, j, k] = todo.back();
    todo.pop_back();
    ++count;
    if (lv.on_outer_face(i, j, k))
      throw RunFailure(fmt::format("hydro_corotating: the star reaches the outer boundary at ({}, {}, {}); the grid is "
                                   "too small or sigma = {} is far too large",
                                   lv.x(i), lv.y(j), lv.z(k), next.sigma));
    const int nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
    for (const auto& q : nb) {
      if (q[2] < 0) continue;  // the mirror image of a stored point
      const std::ptrdiff_t p = lv.at(q[0], q[1], q[2]);
      if (!in_star[p] && h[p] > 1) {
        in_star[p] = 1;
        todo.push_back({q[0], q[1], q[2]});
      }
    }
  }
  double* rho0 = grid_.data(rho0_, 0, 0);
  for (std::size_t p = 0; p < lv.size; ++p) rho0[p] = in_star[p] ? eos_.rho0_from_enthalpy(h[p]) : 0.0;
  fill_thermodynamics();
  return count;
}

double Star::axis_maximum() const {
  const auto line = grid_.line_x(grid_.data(rho0_, 0, 0), 0);
  std::size_t m = 0;
  for (std::size_t i = 1; i < line.size(); ++i)
    if (line[i][1] > line[m][1]) m = i;
  if (m == 0 || m + 1 == line.size())
    throw RunFailure(fmt::format("hydro_corotating: the density maximum lies on the outer face (x = {})", line[m][0]));
  const double a = line[m - 1][1], b = line[m][1], c = line[m + 1][1];
  const double denominator = a - 2 * b + c;
  const double dx = line[m + 1][0] - line[m][0];
  // A flat top (denominator 0) leaves the maximum at the grid point.
  return denominator < 0 ? line[m][0] + 0.5 * dx * (a - c) / denominator : line[m][0];
}

std::string Star::axis_table() const {
  const auto rho0 = grid_.line_x(grid_.data(rho0_, 0, 0), 0);
  const auto chi = grid_.line_x(grid_.data(chi_, 0, 0), 0);
  const auto eta = grid_.line_x(grid_.data(eta_, 0, 0), 0);
  const auto phib = grid_.line_x(grid_.data(puncture_phi_, 0, 0), 0);
  const StarConstants& c = fluid_->constants;
  std::string out = fmt::format("# sigma = {:.12g}, C_B = {:.12g}, xhat_C = {:.12g}; TOV columns at r_iso = sigma |xhat - xhat_C|\n"
                                "# x\trho0\tchi\teta\talpha\trho0_tov\tpsi_tov\talpha_tov\n",
                                c.sigma, c.bernoulli, c.x_c);
  for (std::size_t i = 0; i < rho0.size(); ++i) {
    const double x = rho0[i][0], phi = phib[i][1] + chi[i][1];
    const TovPoint t = tov_at(tov_, c.sigma * std::fabs(x - c.x_c));
    out += fmt::format("{:.10g}\t{:.12e}\t{:.12e}\t{:.12e}\t{:.12e}\t{:.12e}\t{:.12e}\t{:.12e}\n", x, rho0[i][1], chi[i][1],
                       eta[i][1], eta[i][1] / phi, t.rho0, t.psi, t.alpha);
  }
  return out;
}

}  // namespace bhnsid::hydro_corotating
