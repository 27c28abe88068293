#include "bhnsid/core/errors.hpp"
#include "star.hpp"

namespace bhnsid::star {

namespace {
constexpr std::size_t constants_size = 4, report_size = 2 + 2 * constants_size + 6;

void put_constants(std::vector<double>& out, const StarConstants& c) {
  out.insert(out.end(), {c.sigma, c.bernoulli, c.omega_hat, c.x_c});
}
StarConstants constants_at(const double* v) { return StarConstants{v[0], v[1], v[2], v[3]}; }
}  // namespace

void Star::save(core::CheckpointWriter& out) const {
  std::vector<double> now;
  put_constants(now, fluid_->constants);
  now.insert(now.end(), {fluid_->converged ? 1.0 : 0.0, m0_change_, undone_rest_mass_});
  out.put("state", now);
  // What a warm start of another rho_max scales the constants from (warm_start below).
  out.put("rho_max", settings_.rho_max);
  out.put("delta_weight", delta_weight_);
  // Every report as its numbers (iteration, matter_points and converged are small integers, exact
  // in a double).
  std::vector<double> reports;
  for (const StepReport& r : history_) {
    reports.insert(reports.end(), {static_cast<double>(r.iteration), r.change});
    put_constants(reports, r.before);
    put_constants(reports, r.after);
    reports.insert(reports.end(), {r.converged ? 1.0 : 0.0, static_cast<double>(r.matter_points), r.fraction,
                                   r.rest_mass_before, r.m0_change_before, 0.0});
  }
  out.put("history", reports);
}

void Star::restore(const core::CheckpointReader& in) {
  const std::vector<double> now = in.reals("state");
  const std::vector<double> reports = in.reals("history");
  if (now.size() != constants_size + 3 || reports.size() % report_size != 0)
    throw core::InputError("star: the checkpoint's star state is malformed");
  fluid_->constants = constants_at(now.data());
  delta_weight_ = in.real("delta_weight");
  fluid_->converged = now[4] != 0;
  m0_change_ = now[5];
  undone_rest_mass_ = now[6];
  history_.clear();
  for (std::size_t at = 0; at < reports.size(); at += report_size) {
    const double* v = reports.data() + at;
    StepReport r;
    r.iteration = static_cast<int>(v[0]);
    r.change = v[1];
    r.before = constants_at(v + 2);
    r.after = constants_at(v + 2 + constants_size);
    const double* tail = v + 2 + 2 * constants_size;
    r.converged = tail[0] != 0;
    r.matter_points = static_cast<int>(tail[1]);
    r.fraction = tail[2];
    r.rest_mass_before = tail[3];
    r.m0_change_before = tail[4];
    history_.push_back(r);
  }
}

void Star::warm_start(const core::CheckpointReader& in) {
  const std::vector<double> now = in.reals("state");
  if (now.size() != constants_size + 3) throw core::InputError("star: the checkpoint's star state is malformed");
  StarConstants c = constants_at(now.data());
  // The neighbour's sigma and C_B relative to its TOV star, carried over to ours: sigma / (R_iso/Rhat)
  // and C_B / (h_max alpha_c) vary slowly along a sequence, sigma and C_B themselves by as much as
  // R_iso and the central enthalpy do. Its raw sigma (a 20 % step in rho_max puts it ~5 % away) sent
  // the first Newton step over the fold of the sigma model (physics-notes §2.2, §4.4).
  const double rho_theirs = in.real("rho_max");
  if (!(rho_theirs > 0)) throw core::InputError("star: the checkpoint's rho_max is malformed");
  const TovStar theirs = family_.star(rho_theirs);
  c.sigma *= tov_.radius_isotropic / theirs.radius_isotropic;
  c.bernoulli *= (eos_.enthalpy(settings_.rho_max) * tov_.lapse_center) / (eos_.enthalpy(rho_theirs) * theirs.lapse_center);
  // x_c too: the loop moves it with the density maximum, from the same x_a (not steerable).
  fluid_->constants = c;
}

}  // namespace bhnsid::star
