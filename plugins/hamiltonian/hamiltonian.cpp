#include "hamiltonian.hpp"

#include <fmt/format.h>

#include <cmath>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::hamiltonian {

using core::TensorKind;

namespace {

const std::vector<TensorKind> scalar{TensorKind::scalar};

/// Calls fn(std::bool_constant<matter>{}).
template <class Fn>
void with_matter(bool matter, Fn&& fn) {
  if (matter)
    fn(std::true_type{});
  else
    fn(std::false_type{});
}

}  // namespace

HamiltonianEquation::HamiltonianEquation(Grid& grid, const Fluid* fluid, const Puncture* puncture, double matter_scale)
    : grid_(grid), fluid_(fluid), puncture_(puncture), matter_scale_(matter_scale) {
  chi_ = grid.add_field(fields::chi, scalar);
  puncture_phi_ = grid.add_field(fields::puncture_phi, scalar);
  aa_ = grid.add_field(fields::aa, scalar);
}

OuterBoundary HamiltonianEquation::boundary() const {
  return {OuterBoundary::Kind::robin, {1.0}, falloff_centre(fluid_, puncture_)};
}

std::vector<std::string> HamiltonianEquation::coefficients() const {
  // aa_hat is not restricted: its owner (momentum) fills every level, the Bowen-York part analytically.
  // The projections are not either: the star forms them on each level from its restricted inputs.
  if (!fluid_) return {};
  return fluid_->source_inputs();
}

std::string HamiltonianEquation::failure_hint() const {
  if (!fluid_) return {};
  // With rho0 held fixed (not conformally rescaled) solutions exist only up to a fold in sigma.
  return fmt::format("with matter at sigma = {:.9g} the Hamiltonian constraint has no solution above the fold "
                     "sigma_fold of its unscaled source (physics-notes §2.2); sigma may be too large",
                     fluid_->sigma());
}

Sources HamiltonianEquation::sources(int level) const {
  Sources s;
  s.puncture_phi = grid_.data(puncture_phi_, 0, level);
  s.aa = grid_.data(aa_, 0, level);
  if (fluid_) s.matter = matter_sources(grid_, *fluid_, level);
  s.matter_scale = matter_scale_;
  return s;
}

void HamiltonianEquation::residual(const RelaxArgs& args, double* const* out) const {
  const int l = args.level;
  const double* chi = grid_.data(chi_, 0, l);
  const double* rhs = args.rhs ? args.rhs[0] : nullptr;
  const Sources s = sources(l);
  with_matter(fluid_ != nullptr, [&](auto matter) {
    stencil::scalar_residual_any(grid_.level(l), chi, rhs, args.fixed, out[0],
                                 HamiltonianTerm<decltype(matter)::value>{s});
  });
}

void HamiltonianEquation::relax(const RelaxArgs& args) const {
  const int l = args.level;
  double* chi = grid_.data(chi_, 0, l);
  const double* rhs = args.rhs ? args.rhs[0] : nullptr;
  const Sources s = sources(l);
  const stencil::Mirror mirror = [this, l] { grid_.fill_ghosts(chi_, l); };
  with_matter(fluid_ != nullptr, [&](auto matter) {
    stencil::scalar_relax_any(grid_.level(l), chi, rhs, args.fixed, args.omega, mirror,
                              HamiltonianTerm<decltype(matter)::value>{s});
  });
}

void HamiltonianEquation::update_puncture() {
  const double mass = puncture_ ? puncture_->bare_mass() : 0.0;
  const std::array<double, 3> pos = puncture_ ? puncture_->position() : std::array<double, 3>{};
  for (int l = 0; l < grid_.num_levels(); ++l) {
    const Level& lv = grid_.level(l);
    double* out = grid_.data(puncture_phi_, 0, l);
    // A puncture within 1e-6 dx of a point would make 1/r meaningless: the puncture plugin keeps it
    // off the points; this guards against a bug there, never silently.
    if (mass != 0 && !(lv.distance_to_nearest_point(pos) > 1e-6 * lv.dx))
      throw core::RunFailure(fmt::format("hamiltonian: the puncture ({}, {}, {}) lies on a grid point of level {}",
                                         pos[0], pos[1], pos[2], l));
    const double x0 = lv.x(0) - pos[0], h = lv.dx;
#pragma omp parallel for schedule(static)
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j) {
        double* row = out + lv.at(0, j, k);
        const double dy = lv.y(j) - pos[1], dz = lv.z(k) - pos[2], rho2 = dy * dy + dz * dz;
#pragma omp simd
        for (int i = 0; i < lv.nx; ++i) {
          const double dx = x0 + h * i;
          row[i] = mass == 0 ? 0.0 : 0.5 * mass / std::sqrt(dx * dx + rho2);
        }
      }
    grid_.fill_ghosts(puncture_phi_, l);
  }
}

}  // namespace bhnsid::hamiltonian
