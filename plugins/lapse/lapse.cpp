#include "lapse.hpp"

#include <fmt/format.h>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::lapse {

LapseEquation::LapseEquation(Grid& grid, const Fluid* fluid, const Puncture* puncture, double matter_scale)
    : grid_(grid), fluid_(fluid), puncture_(puncture), matter_scale_(matter_scale) {
  eta_ = grid.add_field(fields::eta, {core::TensorKind::scalar});
  grid.add_field(fields::alpha, {core::TensorKind::scalar});
  for (const char* name : {fields::chi, fields::puncture_phi, fields::aa})
    if (!grid.has_field(name))
      throw core::RunFailure(fmt::format("lapse: the field {} is missing; the lapse needs the hamiltonian plugin", name));
}

OuterBoundary LapseEquation::boundary() const {
  return {OuterBoundary::Kind::robin, {1.0}, falloff_centre(fluid_, puncture_)};
}

std::vector<std::string> LapseEquation::coefficients() const {
  // aa_hat is not restricted: its owner (momentum) fills every level, the Bowen-York part analytically.
  // The projections are not either: the star forms them on each level from its restricted inputs.
  if (!fluid_) return {};
  return fluid_->source_inputs();
}

Sources LapseEquation::sources(int level) const {
  Sources s;
  s.chi = grid_.data(grid_.field_id(fields::chi), 0, level);
  s.puncture_phi = grid_.data(grid_.field_id(fields::puncture_phi), 0, level);
  s.aa = grid_.data(grid_.field_id(fields::aa), 0, level);
  if (fluid_) s.matter = matter_sources(grid_, *fluid_, level);
  s.matter_scale = matter_scale_;
  return s;
}

void LapseEquation::residual(const RelaxArgs& args, double* const* out) const {
  const int l = args.level;
  const double* eta = grid_.data(eta_, 0, l);
  const double* rhs = args.rhs ? args.rhs[0] : nullptr;
  const Sources s = sources(l);
  if (fluid_)
    stencil::scalar_residual_any(grid_.level(l), eta, rhs, args.fixed, out[0], LapseTerm<true>{s});
  else
    stencil::scalar_residual_any(grid_.level(l), eta, rhs, args.fixed, out[0], LapseTerm<false>{s});
}

void LapseEquation::relax(const RelaxArgs& args) const {
  const int l = args.level;
  double* eta = grid_.data(eta_, 0, l);
  const double* rhs = args.rhs ? args.rhs[0] : nullptr;
  const Sources s = sources(l);
  const stencil::Mirror mirror = [this, l] { grid_.fill_ghosts(eta_, l); };
  if (fluid_)
    stencil::scalar_relax_any(grid_.level(l), eta, rhs, args.fixed, args.omega, mirror, LapseTerm<true>{s});
  else
    stencil::scalar_relax_any(grid_.level(l), eta, rhs, args.fixed, args.omega, mirror, LapseTerm<false>{s});
}

void EtaLapse::update(Grid& grid, int level) const {
  const int alpha_id = grid.field_id(fields::alpha);
  double* alpha = grid.data(alpha_id, 0, level);
  const double* eta = grid.data(grid.field_id(fields::eta), 0, level);
  const double* chi = grid.data(grid.field_id(fields::chi), 0, level);
  const double* pphi = grid.data(grid.field_id(fields::puncture_phi), 0, level);
  for_stored_points(grid.level(level), [&](std::ptrdiff_t p) { alpha[p] = eta[p] / (pphi[p] + chi[p]); });
  grid.fill_ghosts(alpha_id, level);
}

}  // namespace bhnsid::lapse
