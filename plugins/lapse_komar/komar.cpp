#include "komar.hpp"

#include <fmt/format.h>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::lapse_komar {

KomarEquation::KomarEquation(Grid& grid, const Fluid* fluid, const Puncture& puncture,
                             std::shared_ptr<const Strength> strength)
    : grid_(grid), fluid_(fluid), puncture_(puncture), strength_(std::move(strength)) {
  eta_ = grid.add_field(eta_regular, {core::TensorKind::scalar});
  grid.add_field(fields::alpha, {core::TensorKind::scalar});
  for (const char* name : {fields::chi, fields::puncture_phi, fields::aa})
    if (!grid.has_field(name))
      throw core::RunFailure(
          fmt::format("lapse_komar: the field {} is missing; the lapse needs the hamiltonian plugin", name));
}

OuterBoundary KomarEquation::boundary() const {
  // eta~ = eta + c Mhat/(2 rhat) -> 1 + O(1/r) like eta itself; the same centre as chi (§5.2).
  return {OuterBoundary::Kind::robin, {1.0}, falloff_centre(fluid_, &puncture_)};
}

std::vector<std::string> KomarEquation::coefficients() const {
  if (!fluid_) return {};
  return fluid_->source_inputs();
}

Sources KomarEquation::sources(int level) const {
  Sources s;
  s.chi = grid_.data(grid_.field_id(fields::chi), 0, level);
  s.puncture_phi = grid_.data(grid_.field_id(fields::puncture_phi), 0, level);
  s.aa = grid_.data(grid_.field_id(fields::aa), 0, level);
  if (fluid_) s.matter = matter_sources(grid_, *fluid_, level);
  s.c = strength_->c;
  return s;
}

void KomarEquation::residual(const RelaxArgs& args, double* const* out) const {
  const int l = args.level;
  const double* eta = grid_.data(eta_, 0, l);
  const double* rhs = args.rhs ? args.rhs[0] : nullptr;
  const Sources s = sources(l);
  if (fluid_)
    stencil::scalar_residual_any(grid_.level(l), eta, rhs, args.fixed, out[0], KomarTerm<true>{s});
  else
    stencil::scalar_residual_any(grid_.level(l), eta, rhs, args.fixed, out[0], KomarTerm<false>{s});
}

void KomarEquation::relax(const RelaxArgs& args) const {
  const int l = args.level;
  double* eta = grid_.data(eta_, 0, l);
  const double* rhs = args.rhs ? args.rhs[0] : nullptr;
  const Sources s = sources(l);
  const stencil::Mirror mirror = [this, l] { grid_.fill_ghosts(eta_, l); };
  if (fluid_)
    stencil::scalar_relax_any(grid_.level(l), eta, rhs, args.fixed, args.omega, mirror, KomarTerm<true>{s});
  else
    stencil::scalar_relax_any(grid_.level(l), eta, rhs, args.fixed, args.omega, mirror, KomarTerm<false>{s});
}

void KomarLapse::update(Grid& grid, int level) const {
  const int alpha_id = grid.field_id(fields::alpha);
  double* alpha = grid.data(alpha_id, 0, level);
  const double* eta = grid.data(grid.field_id(eta_regular), 0, level);
  const double* chi = grid.data(grid.field_id(fields::chi), 0, level);
  const double* pphi = grid.data(grid.field_id(fields::puncture_phi), 0, level);
  const double c = strength_->c;
  for_stored_points(grid.level(level), [&](std::ptrdiff_t p) { alpha[p] = alpha_of(eta[p], chi[p], pphi[p], c); });
  grid.fill_ghosts(alpha_id, level);
}

}  // namespace bhnsid::lapse_komar
