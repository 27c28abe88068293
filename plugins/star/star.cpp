#include "star.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "outer_newton.hpp"
#include "tov_profile.hpp"

namespace bhnsid::star {

using core::RunFailure;

Star::Star(Grid& grid, const Eos& eos, const TovFamily& family, const Lapse& lapse, Flow& flow, StarSettings settings,
           std::shared_ptr<StarFluid> fluid, const Puncture* hole)
    : grid_(grid), eos_(eos), family_(family), lapse_(lapse), settings_(settings), fluid_(std::move(fluid)), hole_(hole) {
  fluid_->attach(grid, flow);
  rho0_ = grid.field_id(fields::rho0);
  press_ = grid.field_id(fields::press);
  enthalpy_ = grid.field_id(fields::enthalpy);
  chi_ = grid.field_id(fields::chi);
  lapse_regular_ = grid.field_id(lapse.regular_part());
  puncture_phi_ = grid.field_id(fields::puncture_phi);
  tov_ = family.star(settings.rho_max);
  fluid_->initial_mass = tov_.rest_mass;
  fluid_->constants.x_c = 0.5 * (1.0 + settings.x_a);
  fluid_->robin_centre = fluid_->constants.x_c;
  delta_weight_ = settings.model_hole_delta;
  fluid_->constants.sigma = settings.sigma_guess > 0 ? settings.sigma_guess : tov_.radius_isotropic / rhat_star();
  fluid_->constants.bernoulli = eos.enthalpy(settings.rho_max) * tov_.lapse_center;
  // A single star may be held at a rotation rate (a test of the flow); a binary's comes from its orbit.
  if (!hole) fluid_->constants.omega_hat = settings.test_omega_hat;
}

double Star::hole_delta() const {
  if (!hole_ || !(hole_->bare_mass() > 0)) return 0.0;
  const double d = fluid_->constants.x_c - hole_->position()[0];
  return 0.5 * hole_->bare_mass() / d;
}

double Star::model_sigma(double sigma) const {
  const double g = 1.0 + delta_weight_ * hole_delta();
  return sigma * g * g;
}

double Star::kepler_omega() const {
  const StarConstants& c = fluid_->constants;
  // Only the first step's start for Omegahat: the initial TOV profile in the binary's fields can hold
  // more than the family's maximum rest mass (rho_max = 0.155, x_a = 0.5 at n = 32: 0.201 > 0.180),
  // where M_NS(M0) has no answer; the heaviest star's mass is start enough.
  const double m0 = std::min(fluid_->rest_mass(), family_.maximum_rest_mass_star().rest_mass);
  const double m_ns = family_.adm_mass_from_rest_mass(m0) / c.sigma;
  const double d = c.x_c - hole_->position()[0];
  return std::sqrt((hole_->bare_mass() + m_ns) / (d * d * d));
}

void Star::set_initial() {
  const Level& lv = grid_.finest();
  // The hole (placed at SETUP) shrinks the star's coordinate size: sigma_0 = R_iso/(Rhat phi_ext^2).
  if (hole_ && settings_.sigma_guess == 0) {
    const double g = 1.0 + hole_delta();
    fluid_->constants.sigma /= g * g;
  }
  // The TOV star placed on hatted radius Rhat whatever the initial sigma (physics-notes §4.7): a
  // sigma_guess away from R_iso/Rhat then starts from the same density with other field constants.
  const double scale = tov_.radius_isotropic / rhat_star(), x_c = fluid_->constants.x_c;
  double* rho0 = grid_.data(rho0_, 0, 0);
  double* chi = grid_.data(chi_, 0, 0);
  // The lapse's regular part is alpha phi without the puncture's term: alpha_TOV psi_TOV in the star.
  double* regular = grid_.data(lapse_regular_, 0, 0);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        const TovPoint t = tov_at(tov_, scale * std::hypot(lv.x(i) - x_c, lv.y(j), lv.z(k)));
        rho0[p] = t.rho0;
        chi[p] = t.psi;
        regular[p] = t.alpha * t.psi;
      }
  for (int f : {chi_, lapse_regular_}) grid_.fill_ghosts(f, 0);
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

/// alpha on the finest level from the lapse, ghosts filled, for interpolation.
std::vector<double> lapse_field(Grid& grid, const Lapse& lapse) {
  const double* alpha = lapse_on(grid, lapse, 0);
  return std::vector<double>(alpha, alpha + grid.finest().size);
}

/// phi = puncture_phi + chi on the finest level, ghosts filled, for interpolation.
std::vector<double> conformal_factor_field(Grid& grid, int chi, int puncture_phi) {
  const Level& lv = grid.finest();
  std::vector<double> phi(lv.size, 1.0);
  const double* c = grid.data(chi, 0, 0);
  const double* b = grid.data(puncture_phi, 0, 0);
  for (std::size_t p = 0; p < lv.size; ++p) phi[p] = b[p] + c[p];
  grid.fill_ghosts(phi.data(), Parity{}, 0);
  return phi;
}

}  // namespace

void Star::retreat() {
  if (history_.empty() || history_.back().converged || !settings_.iterate)
    throw RunFailure("star: no outer step of the star to undo (its last step changed nothing)");
  const StepReport& last = history_.back();
  fluid_->constants = last.before;
  m0_change_ = last.m0_change_before;
  undone_rest_mass_ = last.rest_mass_before;
  history_.pop_back();
}

StepReport Star::step(double fraction) {
  StepReport report;
  report.iteration = static_cast<int>(history_.size()) + 1;
  report.fraction = fraction;
  report.m0_change_before = m0_change_;
  // Set again below when this step converges: the loop may go on for another check's sake, and a
  // step that resets the density must let the black hole follow.
  fluid_->converged = false;
  StarConstants& now = fluid_->constants;
  report.before = now;
  report.after = now;
  Flow& flow = fluid_->flow();
  if (!settings_.iterate) {
    // The density and the constants are held; a flow with a field of its own still follows the
    // fields, and the star is settled once that field is.
    report.change = flow.prepare(grid_, {now.sigma, now.omega_hat, now.bernoulli});
    report.converged = report.change < settings_.tolerance;
    fluid_->converged = report.converged;
    history_.push_back(report);
    return report;
  }
  // The first step with a hole starts Omegahat from Kepler; the flow sees that start too.
  const double omega_start = !hole_ ? now.omega_hat : now.omega_hat > 0 ? now.omega_hat : kepler_omega();
  const FlowConstants start{now.sigma, omega_start, now.bernoulli};
  flow.prepare(grid_, start);
  // The fields of the last solve, read by the Newton solve and by the reset (unchanged between them).
  const std::vector<double> alpha = lapse_field(grid_, lapse_);
  const std::vector<double> phi = conformal_factor_field(grid_, chi_, puncture_phi_);
  const double rhat = rhat_star(), h_max = eos_.enthalpy(settings_.rho_max);
  auto at = [&](const std::vector<double>& f, double x) { return grid_.interpolate(f.data(), Parity{}, 0, {x, 0, 0}); };
  const PointResidual residual = [&flow](std::size_t p, double a, double ph, double w, double c, double h) {
    return flow.axis_residual(p, a, ph, w, c, h);
  };
  NewtonResult solved;
  // The axis points and the sigma-model of alpha and phi there (without a hole model_sigma(s) = s).
  std::vector<double> xs;
  std::vector<AxisPoint> points;
  const FieldModel model = [&](double s) {
    const FrozenProfileSolution m = family_.frozen_profile(settings_.rho_max, rhat, model_sigma(s));
    ModelValues v;
    for (const AxisPoint& q : points) {
      v.alpha.push_back(m.alpha_at(q.rhat));
      v.phi.push_back(m.phi_at(q.rhat));
    }
    return v;
  };
  if (!hole_) {
    // The centre (h = h_max) and the surface point xhat = 1 (h = 1); without a hole xhat_A is
    // equivalent to xhat = 1 by symmetry and Omegahat is held, so two points fix (sigma, C_B) (§9 T1).
    xs = {now.x_c, 1.0};
    points = {{0.0, at(alpha, xs[0]), at(phi, xs[0]), h_max}, {1.0 - now.x_c, at(alpha, xs[1]), at(phi, xs[1]), 1.0}};
    flow.freeze_axis(grid_, xs, start);
    // C_B from the surface point at the old sigma: the surface equation alone fixes it there.
    solved = solve_sigma_bernoulli(points, model, residual, now.sigma, now.omega_hat, points[1].enthalpy * points[1].alpha);
  } else {
    xs = {1.0, settings_.x_a, now.x_c};
    for (std::size_t p = 0; p < 3; ++p)
      points.push_back({std::fabs(xs[p] - now.x_c), at(alpha, xs[p]), at(phi, xs[p]), p == 2 ? h_max : 1.0});
    flow.freeze_axis(grid_, xs, start);
    for (;;) {
      try {
        solved = solve_sigma_omega_bernoulli(points, model, residual, now.sigma, omega_start, now.bernoulli);
        break;
      } catch (const core::RunFailure& e) {
        if (delta_weight_ == 0 || hole_delta() == 0) {
          if (report.model_note.empty()) throw;
          throw core::RunFailure(fmt::format("{} (after: {})", e.what(), report.model_note));
        }
        const double was = delta_weight_;
        delta_weight_ = delta_weight_ > 0.2 ? 0.5 * delta_weight_ : 0.0;
        report.model_note += fmt::format("{}the sigma-model with {:.3g} of the hole's delta failed ({}); now {:.3g}",
                                         report.model_note.empty() ? "" : "; ", was, e.what(), delta_weight_);
      }
    }
  }
  const double omega = solved.omega_hat;
  // A flow whose Newton model linearises its own field about the current Omegahat trusts it only so
  // far: a longer step is shortened like a retreat's, every constant the same fraction of the way.
  const double omega_limit = flow.omega_step_limit();
  if (hole_ && now.omega_hat > 0 && omega_limit > 0) {
    const double step = std::fabs(omega / now.omega_hat - 1);
    if (step > omega_limit) {
      fraction = std::min(fraction, omega_limit / step);
      report.fraction = fraction;
    }
  }
  // A retreat's shorter step: every constant of the Newton solution the same fraction of the way,
  // so that the density stays between two consistent states.
  report.after.sigma = now.sigma + fraction * (solved.sigma - now.sigma);
  report.after.bernoulli = now.bernoulli + fraction * (solved.bernoulli - now.bernoulli);
  // (The first step with a hole sets Omegahat from nothing: it has no earlier value to lie between.)
  report.after.omega_hat = now.omega_hat > 0 ? now.omega_hat + fraction * (omega - now.omega_hat) : omega;
  report.change = std::max(std::fabs(solved.sigma / now.sigma - 1), std::fabs(solved.bernoulli / now.bernoulli - 1));
  if (hole_ && now.omega_hat > 0) report.change = std::max(report.change, std::fabs(omega / now.omega_hat - 1));
  if (hole_ && now.omega_hat == 0) report.change = std::max(report.change, 1.0);  // the first step sets Omegahat
  // Converged: keep the density the fields were just solved with, so the output is consistent;
  // the Bernoulli equation then holds to about the tolerance (physics-notes §4.2).
  // M0 moves with sigma and the density: the last reset's change of M0 must have settled too (§4.2).
  if (std::max(report.change, m0_change_) < settings_.tolerance && report.iteration > 1 && fraction == 1) {
    report.converged = true;
    fluid_->converged = true;
    report.after = now;
    report.matter_points = -1;
    history_.push_back(report);
    return report;
  }
  // After a retreat the density is still the undone step's: M0 before it is the one it recorded.
  const double m0_before = undone_rest_mass_ > 0 ? undone_rest_mass_ : fluid_->rest_mass();
  undone_rest_mass_ = 0;
  report.rest_mass_before = m0_before;
  flow.set_constants(grid_, {report.after.sigma, report.after.omega_hat, report.after.bernoulli});
  report.matter_points = bernoulli_reset(report.after, alpha, phi);
  now.sigma = report.after.sigma;
  now.bernoulli = report.after.bernoulli;
  now.omega_hat = report.after.omega_hat;
  now.x_c = axis_maximum();
  const double m0 = fluid_->rest_mass();
  // The reset places matter by the sigma-modelled fields; the rest mass (and every source) reads
  // the last solve's, in which the flow there may be superluminal: no state to go on from.
  if (!std::isfinite(m0)) {
    const std::string where = fluid_->flow().acausal_matter(grid_, fluid_->flow_constants());
    throw RunFailure(fmt::format("star: after the Bernoulli reset the {} flow has no timelike velocity in the star in the "
                                 "last solve's fields (sigma = {}, Omegahat = {}, C_B = {}){}; the star reaches the "
                                 "hole's light cylinder, or the step moved the constants too far",
                                 fluid_->flow().kind(), now.sigma, now.omega_hat, now.bernoulli,
                                 where.empty() ? std::string() : ": " + where));
  }
  m0_change_ = m0_before > 0 ? std::fabs(m0 / m0_before - 1) : 1.0;
  report.change = std::max(report.change, m0_change_);
  report.after = now;
  history_.push_back(report);
  return report;
}

int Star::bernoulli_reset(const StarConstants& next, const std::vector<double>& alpha, const std::vector<double>& phi) {
  const Level& lv = grid_.finest();
  const StarConstants& now = fluid_->constants;
  const double rhat = rhat_star();
  const FrozenProfileSolution model_new = family_.frozen_profile(settings_.rho_max, rhat, model_sigma(next.sigma));
  const FrozenProfileSolution model_old = family_.frozen_profile(settings_.rho_max, rhat, model_sigma(now.sigma));
  // h = C_B G from the flow's first integral with the sigma-modelled alpha~ and phi~ (§3, §4.8); -1
  // where G is undefined (near the hole, beyond the light cylinder).
  std::vector<double> modelled_alpha(lv.size, 1.0), modelled_phi(lv.size, 1.0), h(lv.size, 0.0);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        const double r = std::hypot(lv.x(i) - now.x_c, lv.y(j), lv.z(k));
        modelled_alpha[p] = alpha[p] + model_new.alpha_at(r) - model_old.alpha_at(r);
        modelled_phi[p] = phi[p] + model_new.phi_at(r) - model_old.phi_at(r);
      }
  fluid_->flow().enthalpy(grid_, {next.sigma, next.omega_hat, next.bernoulli}, modelled_alpha.data(), modelled_phi.data(),
                          h.data());
  // The star is the 6-connected component of {h > 1} containing the point nearest xhat_C (§3).
  const int i0 = static_cast<int>(std::lround((now.x_c - lv.origin[0]) / lv.dx));
  const int j0 = lv.n / 2, k0 = lv.z_symmetry ? 0 : lv.n / 2;
  if (!(h[lv.at(i0, j0, k0)] > 1))
    throw RunFailure(fmt::format("star: the Bernoulli reset leaves no matter at the centre xhat_C = {} "
                                 "(h = {} there, sigma = {}, Omegahat = {}, C_B = {})",
                                 now.x_c, h[lv.at(i0, j0, k0)], next.sigma, next.omega_hat, next.bernoulli));
  int excision = -1;
  if (hole_) {
    try {
      excision = grid_.mask_id(fields::excision_mask);
    } catch (const std::exception&) {
      excision = -1;  // no shift equation: no cube
    }
  }
  const std::uint8_t* cube = excision >= 0 ? grid_.mask(excision, 0) : nullptr;
  std::vector<std::uint8_t> in_star(lv.size, 0);
  std::vector<std::array<int, 3>> todo{{i0, j0, k0}};
  in_star[lv.at(i0, j0, k0)] = 1;
  int count = 0;
  while (!todo.empty()) {
    const auto [i, j, k] = todo.back();
    todo.pop_back();
    ++count;
    const std::ptrdiff_t at = lv.at(i, j, k);
    if (lv.on_outer_face(i, j, k))
      throw RunFailure(fmt::format("star: the star reaches the outer boundary at ({}, {}, {}); the grid is "
                                   "too small or sigma = {} is far too large",
                                   lv.x(i), lv.y(j), lv.z(k), next.sigma));
    if (cube && cube[at])
      throw RunFailure(fmt::format("star: Roche limit / mass shedding: the star reaches the black hole's "
                                   "excision cube at ({}, {}, {}) (sigma = {}, Omegahat = {}, C_B = {})",
                                   lv.x(i), lv.y(j), lv.z(k), next.sigma, next.omega_hat, next.bernoulli));
    if (hole_ && j == j0 && k == k0 && lv.x(i) < settings_.x_a - lv.dx)
      throw RunFailure(fmt::format("star: Roche lobe overflow: the star extends along the axis to x = {}, "
                                   "past xhat_A = {} towards the hole (sigma = {}, Omegahat = {}, C_B = {})",
                                   lv.x(i), settings_.x_a, next.sigma, next.omega_hat, next.bernoulli));
    const int nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
    for (const auto& q : nb) {
      if (q[2] < 0) continue;  // the mirror image of a stored point
      const std::ptrdiff_t p = lv.at(q[0], q[1], q[2]);
      // A point of the star next to one where the Bernoulli argument is negative: the star's
      // surface would be where the modelled lapse vanishes (the hole, the light cylinder).
      if (h[p] < 0)
        throw RunFailure(fmt::format("star: the {} flow's first integral gives no enthalpy next to the star at ({}, "
                                     "{}, {}) (sigma = {}, Omegahat = {}; for corotation alpha^2 - phi^4 |beta + "
                                     "Omegahat xi|^2 < 0 there)",
                                     fluid_->flow().kind(), lv.x(q[0]), lv.y(q[1]), lv.z(q[2]), next.sigma,
                                     next.omega_hat));
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
    throw RunFailure(fmt::format("star: the density maximum lies on the outer face (x = {})", line[m][0]));
  const double a = line[m - 1][1], b = line[m][1], c = line[m + 1][1];
  const double denominator = a - 2 * b + c;
  const double dx = line[m + 1][0] - line[m][0];
  // A flat top (denominator 0) leaves the maximum at the grid point.
  return denominator < 0 ? line[m][0] + 0.5 * dx * (a - c) / denominator : line[m][0];
}

std::string Star::axis_table() const {
  const auto rho0 = grid_.line_x(grid_.data(rho0_, 0, 0), 0);
  const auto chi = grid_.line_x(grid_.data(chi_, 0, 0), 0);
  const auto regular = grid_.line_x(grid_.data(lapse_regular_, 0, 0), 0);
  const auto alpha = grid_.line_x(lapse_on(grid_, lapse_, 0), 0);
  const auto phib = grid_.line_x(grid_.data(puncture_phi_, 0, 0), 0);
  const StarConstants& c = fluid_->constants;
  std::string out = fmt::format("# sigma = {:.12g}, C_B = {:.12g}, xhat_C = {:.12g}; TOV columns at r_iso = sigma |xhat - xhat_C|\n"
                                "# x\trho0\tchi\tlapse_regular\talpha\trho0_tov\tpsi_tov\talpha_tov\n",
                                c.sigma, c.bernoulli, c.x_c);
  for (std::size_t i = 0; i < rho0.size(); ++i) {
    const double x = rho0[i][0];
    const TovPoint t = tov_at(tov_, c.sigma * std::fabs(x - c.x_c));
    out += fmt::format("{:.10g}\t{:.12e}\t{:.12e}\t{:.12e}\t{:.12e}\t{:.12e}\t{:.12e}\t{:.12e}\n", x, rho0[i][1], chi[i][1],
                       regular[i][1], alpha[i][1], t.rho0, t.psi, t.alpha);
  }
  return out;
}

}  // namespace bhnsid::star
