#include "momentum.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::momentum {

using core::TensorKind;

namespace {

const std::vector<TensorKind> scalar{TensorKind::scalar};
const std::vector<TensorKind> vector{TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z};
const std::vector<TensorKind> symmetric{TensorKind::tensor_xx, TensorKind::tensor_xy, TensorKind::tensor_xz,
                                        TensorKind::tensor_yy, TensorKind::tensor_yz, TensorKind::tensor_zz};

/// Calls fn(MomentumLower<matter>{s}).
template <class Fn>
void with_lower(const Sources& s, bool matter, Fn&& fn) {
  if (matter)
    fn(MomentumLower<true>{s});
  else
    fn(MomentumLower<false>{s});
}

int required_field(const Grid& grid, const std::string& name, const char* owner) {
  if (!grid.has_field(name))
    throw core::RunFailure(fmt::format(
        "momentum: the field '{}' is missing at SETUP; the momentum constraint reads it, registered by {}: add that "
        "plugin to plugins (or, in a test, a plugin that registers '{}' before momentum.setup)",
        name, owner, name));
  return grid.field_id(name);
}

}  // namespace

MomentumEquation::MomentumEquation(Grid& grid, const Lapse* lapse, Weight weight, const Fluid* fluid,
                                   const Puncture* puncture, double source_scale)
    : grid_(grid), fluid_(fluid), puncture_(puncture), source_scale_(source_scale), weight_kind_(weight) {
  chi_ = required_field(grid, fields::chi, "the hamiltonian plugin");
  puncture_phi_ = required_field(grid, fields::puncture_phi, "the hamiltonian plugin");
  weight_ = grid.add_field(fields::ansatz_weight, scalar);
  if (weight == Weight::lapse) {
    if (!lapse)
      throw core::InputError("momentum.weight = lapse: no plugin implements 'lapse' (add one to plugins:, or set "
                             "momentum.weight: unit)");
    weight_source_ = required_field(grid, lapse->regular_part(), "the plugin implementing 'lapse' (its regular part)");
  } else {
    for (int l = 0; l < grid.num_levels(); ++l) {
      double* q = grid.data(weight_, 0, l);
      std::fill(q, q + grid.level(l).size, 1.0);
    }
  }
  w_ = grid.add_field(fields::wvec, vector, core::TimeParity::odd);
  ahat_ = grid.add_field(fields::ahat, symmetric, core::TimeParity::odd);
  // Registered by the hamiltonian plugin when it is active; the same kinds return that field.
  aa_ = grid.add_field(fields::aa, scalar);
}

OuterBoundary MomentumEquation::boundary() const {
  OuterBoundary b;
  b.kind = OuterBoundary::Kind::robin;
  b.u_inf = {0.0, 0.0, 0.0};
  b.centre = {0.0, 0.0, 0.0};
  return b;
}

std::vector<std::string> MomentumEquation::coefficients() const {
  // chi and the lapse's regular part are unknowns (the solver keeps them on every level)
  // and puncture_phi is analytic on every level, so only the star's inputs are restricted.
  if (!fluid_) return {};
  return fluid_->source_inputs();
}

void MomentumEquation::refresh_weight(int level) const {
  if (weight_kind_ != Weight::lapse) return;
  const double* from = grid_.data(weight_source_, 0, level);
  std::copy(from, from + grid_.level(level).size, grid_.data(weight_, 0, level));
}

Sources MomentumEquation::sources(int level) const {
  const Level& lv = grid_.level(level);
  Sources s;
  s.chi = grid_.data(chi_, 0, level);
  // The sweeps read the lapse's regular part where it lives (no copy per sweep); wvec_weight holds
  // the finest level's copy for the IRE, refreshed with the curvature.
  s.weight = grid_.data(weight_kind_ == Weight::lapse ? weight_source_ : weight_, 0, level);
  s.puncture_phi = grid_.data(puncture_phi_, 0, level);
  s.sy = lv.sy;
  s.sz = lv.sz;
  s.inv_2h = 0.5 / lv.dx;
  s.source_scale = source_scale_;
  if (fluid_) s.matter = matter_sources(grid_, *fluid_, level);
  return s;
}

void MomentumEquation::residual(const RelaxArgs& args, double* const* out) const {
  const int l = args.level;
  const stencil::ConstComponents w{grid_.data(w_, 0, l), grid_.data(w_, 1, l), grid_.data(w_, 2, l)};
  const Sources s = sources(l);
  with_lower(s, fluid_ != nullptr, [&](const auto& lower) {
    stencil::vector_residual_any(grid_.level(l), w, args.rhs, args.fixed, {out[0], out[1], out[2]}, lower);
  });
}

void MomentumEquation::relax(const RelaxArgs& args) const {
  const int l = args.level;
  const stencil::Components w{grid_.data(w_, 0, l), grid_.data(w_, 1, l), grid_.data(w_, 2, l)};
  const Sources s = sources(l);
  const stencil::Mirror mirror = [this, l] { grid_.fill_ghosts(w_, l); };
  with_lower(s, fluid_ != nullptr, [&](const auto& lower) {
    stencil::vector_relax_any(grid_.level(l), w, args.rhs, args.fixed, args.omega, mirror, lower);
  });
}

CurvatureChange MomentumEquation::fill_curvature() const {
  refresh_weight(0);
  const Level& lv = grid_.finest();
  const double* q = grid_.data(weight_, 0, 0);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i)
        if (!(q[lv.at(i, j, k)] > 0))
          throw core::RunFailure(fmt::format(
              "momentum: the ansatz weight q = {:.6g} at xhat = ({:.6g}, {:.6g}, {:.6g}) is not positive (momentum.weight "
              "= lapse takes the lapse's regular part; momentum.weight: unit takes q = 1)",
              q[lv.at(i, j, k)], lv.x(i), lv.y(j), lv.z(k)));
  return momentum::fill_curvature(grid_, CurvatureFields{w_, chi_, weight_, ahat_, aa_}, puncture_);
}

}  // namespace bhnsid::momentum
