#include "fluid.hpp"

#include <cmath>
#include <memory>

#include "bhnsid/core/errors.hpp"
#include "kinematics.hpp"

namespace bhnsid::hydro_corotating {

void StarFluid::attach(Grid& grid, const Lapse& lapse) {
  grid_ = &grid;
  lapse_ = &lapse;
  const std::vector<core::TensorKind> scalar{core::TensorKind::scalar};
  const std::vector<core::TensorKind> vector{core::TensorKind::vector_x, core::TensorKind::vector_y,
                                             core::TensorKind::vector_z};
  rho0_ = grid.add_field(fields::rho0, scalar);
  press_ = grid.add_field(fields::press, scalar);
  enthalpy_ = grid.add_field(fields::enthalpy, scalar);
  energy_ = grid.add_field(fields::matter_energy, scalar);
  trace_ = grid.add_field(fields::matter_trace, scalar);
  momentum_ = grid.add_field(fields::matter_momentum, vector, core::TimeParity::odd);
  chi_ = grid.field_id(fields::chi);
  puncture_phi_ = grid.field_id(fields::puncture_phi);
}

namespace {

/// The level's arrays the projections read; beta is null without a shift equation (beta = 0).
struct Inputs {
  const double *rho0, *press, *enthalpy, *chi, *alpha, *puncture_phi;
  const double* beta[3] = {nullptr, nullptr, nullptr};
};

/// Calls fn(p, ux, uy, uz, lorentz2, alpha, phi) per stored point: the loop shared by the
/// projections and the rest mass. The matter is selected where rho0 > 0 by the
/// callers (not branched on), so that the rows vectorise.
template <bool Shift, class Fn>
void for_points(const Level& lv, const Inputs& in, double omega_hat, Fn&& fn) {
  for_stored_points_xy(lv, [&](std::ptrdiff_t p, double x, double y) {
    // U = beta + Omegahat xi, xi = (-y, x, 0).
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

/// Refreshes alpha on `level` from the lapse and gathers the arrays.
Inputs inputs(Grid& grid, const Lapse& lapse, int level, int rho0, int press, int enthalpy, int chi, int puncture_phi) {
  Inputs in{grid.data(rho0, 0, level), grid.data(press, 0, level), grid.data(enthalpy, 0, level),
            grid.data(chi, 0, level), lapse_on(grid, lapse, level), grid.data(puncture_phi, 0, level)};
  if (grid.has_field(fields::shift)) {
    const int beta = grid.field_id(fields::shift);
    for (int c = 0; c < 3; ++c) in.beta[c] = grid.data(beta, c, level);
  }
  return in;
}

}  // namespace

void StarFluid::update_sources(Grid& grid, int level) const {
  const Level& lv = grid.level(level);
  const Inputs in = inputs(grid, *lapse_, level, rho0_, press_, enthalpy_, chi_, puncture_phi_);
  double* energy = grid.data(energy_, 0, level);
  double* trace = grid.data(trace_, 0, level);
  double* j[3] = {grid.data(momentum_, 0, level), grid.data(momentum_, 1, level), grid.data(momentum_, 2, level)};
  auto fill = [&](std::ptrdiff_t p, double ux, double uy, double uz, double w2, double alpha, double) {
    const double rho0 = in.rho0[p];
    const Projections m = projections(rho0, in.press[p], in.enthalpy[p], w2, alpha, ux, uy, uz);
    // Outside the star W may be NaN (U superluminal far out); the select drops it.
    const bool matter = rho0 > 0;
    energy[p] = matter ? m.energy : 0.0;
    trace[p] = matter ? m.trace : 0.0;
    j[0][p] = matter ? m.jx : 0.0;
    j[1][p] = matter ? m.jy : 0.0;
    j[2][p] = matter ? m.jz : 0.0;
  };
  if (in.beta[0])
    for_points<true>(lv, in, constants.omega_hat, fill);
  else
    for_points<false>(lv, in, constants.omega_hat, fill);
}

double StarFluid::rest_mass() const {
  if (!grid_) return 0.0;
  Grid& grid = *grid_;
  const Level& lv = grid.finest();
  const Inputs in = inputs(grid, *lapse_, 0, rho0_, press_, enthalpy_, chi_, puncture_phi_);
  // Every stored point is written (integrate reads no ghost), so no zero fill first.
  const auto density = std::make_unique_for_overwrite<double[]>(lv.size);
  double* d = density.get();
  auto fill = [&](std::ptrdiff_t p, double, double, double, double w2, double, double phi) {
    const double phi2 = phi * phi;
    d[p] = in.rho0[p] > 0 ? in.rho0[p] * std::sqrt(w2) * phi2 * phi2 * phi2 : 0.0;
  };
  if (in.beta[0])
    for_points<true>(lv, in, constants.omega_hat, fill);
  else
    for_points<false>(lv, in, constants.omega_hat, fill);
  const double s = constants.sigma;
  return s * s * s * grid.integrate(d, Parity{}, 0);
}

std::optional<std::array<double, 3>> StarFluid::superluminal_matter() const {
  if (!grid_) return std::nullopt;
  const Level& lv = grid_->finest();
  const Inputs in = inputs(*grid_, *lapse_, 0, rho0_, press_, enthalpy_, chi_, puncture_phi_);
  // Only asked after a failure: the branch in the loop and the search for the point cost nothing.
  std::ptrdiff_t found = -1;
  auto find = [&](std::ptrdiff_t p, double, double, double, double w2, double, double) {
    if (found < 0 && in.rho0[p] > 0 && !std::isfinite(w2)) found = p;
  };
  if (in.beta[0])
    for_points<true>(lv, in, constants.omega_hat, find);
  else
    for_points<false>(lv, in, constants.omega_hat, find);
  if (found < 0) return std::nullopt;
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i)
        if (lv.at(i, j, k) == found) return std::array<double, 3>{lv.x(i), lv.y(j), lv.z(k)};
  return std::nullopt;
}

}  // namespace bhnsid::hydro_corotating
