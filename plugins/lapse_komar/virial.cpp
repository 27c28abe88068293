#include "virial.hpp"

#include <algorithm>
#include <cmath>

#include "bhnsid/interfaces/falloff.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "komar.hpp"

namespace bhnsid::lapse_komar {

VirialMeasure measure_virial(const Grid& grid, double c, const Puncture& hole, const std::array<double, 3>& centre) {
  const Level& lv = grid.finest();
  const double bare_mass = hole.bare_mass();
  const std::array<double, 3> position = hole.position();
  const double* rho0 = grid.has_field(fields::rho0) ? grid.data(grid.field_id(fields::rho0), 0, 0) : nullptr;
  const double s_min = enclosing_half_width(lv, rho0, &position);
  const double b_regular = falloff_fit(lv, grid.data(grid.field_id(eta_regular), 0, 0), 1.0, centre, s_min).coefficient;
  const double b_chi = falloff_fit(lv, grid.data(grid.field_id(fields::chi), 0, 0), 1.0, centre, s_min).coefficient;
  // The puncture's Mhat/(2 rhat_BH) about the falloff centre: its 1/r coefficient is Mhat/2 (the
  // dipole from the offset cancels in each surface average).
  return {b_regular - 0.5 * c * bare_mass, b_chi + 0.5 * bare_mass};
}

double VirialSecant::next(double c, const VirialMeasure& m, double bare_mass, double fraction) {
  const double g = m.residual();
  // dg/dc = -Mhat/2 + dB(eta~)/dc; the second part (kappa's response) is small and of the same sign.
  double slope = -0.5 * bare_mass;
  if (last_ && std::fabs(c - last_->c) > 1e-12) {
    const double secant = (g - last_->g) / (c - last_->c);
    if (secant < -0.1 * bare_mass && secant > -4.0 * bare_mass) slope = secant;
  }
  last_ = Point{c, g};
  const double step = std::clamp(-fraction * g / slope, -0.25, 0.25);
  return c + step;
}

}  // namespace bhnsid::lapse_komar
