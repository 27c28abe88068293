#include "binary.hpp"

#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::puncture {

HoleValues scaled_hole(const Grid& grid, const Fluid& fluid, const TovFamily& family, double mass_ratio,
                       double rest_mass) {
  if (!(rest_mass > 0) || !std::isfinite(rest_mass))
    throw core::RunFailure(fmt::format("puncture: the star's rest mass M0 = {} leaves no black-hole mass "
                                       "(Mhat_BH = mu_bn M_NS(M0)/sigma)",
                                       rest_mass));
  HoleValues h;
  // Throws (a RunFailure) above the maximum rest mass of the TOV family: the star is too heavy.
  h.mass = mass_ratio * family.adm_mass_from_rest_mass(rest_mass) / fluid.sigma();
  h.position = {-fluid.centre()[0] / mass_ratio, 0.0, 0.0};
  // 1/r at a grid point of any level would be infinite: a hole within 1e-6 dx of one moves along x
  // by 1e-3 of the finest spacing (a shift far below the truncation error), and says so.
  const double step = 1e-3 * grid.finest().dx;
  for (int tries = 0; tries < 8; ++tries) {
    bool on_point = false;
    for (int l = 0; l < grid.num_levels() && !on_point; ++l)
      on_point = !(grid.level(l).distance_to_nearest_point(h.position) > 1e-6 * grid.level(l).dx);
    if (!on_point) return h;
    h.moved = fmt::format("xhat_BH = {:.12g} lay on a grid point; moved by {:.3g}", h.position[0], step);
    h.position[0] += step;
  }
  throw core::RunFailure(fmt::format("puncture: xhat_BH = {} stays on a grid point", h.position[0]));
}

double balancing_momentum(Grid& grid, const Fluid& fluid) {
  fluid.update_sources(grid, 0);
  const Level& lv = grid.finest();
  const double* chi = grid.data(grid.field_id(fields::chi), 0, 0);
  const double* punc = grid.data(grid.field_id(fields::puncture_phi), 0, 0);
  const double* jy = grid.data(grid.field_id(fields::matter_momentum), 1, 0);
  const auto density = std::make_unique_for_overwrite<double[]>(lv.size);  // integrate reads no ghost
  double* d = density.get();
  for_stored_points(lv, [&](std::ptrdiff_t p) {
    const double phi = punc[p] + chi[p], phi2 = phi * phi, phi4 = phi2 * phi2;
    d[p] = phi4 * phi4 * phi2 * jy[p];
  });
  const double s = fluid.sigma();
  // j^y is even under z -> -z (physics-notes §8): the default parity integrates the mirror image.
  return -s * s * grid.integrate(d, Parity{}, 0);
}

double irreducible_bare_mass(double bare_now, double irreducible_now, double target) {
  if (!(irreducible_now > 0) || !std::isfinite(irreducible_now))
    throw core::RunFailure(fmt::format("puncture: the apparent horizon's mass is {} after the last solve: no irreducible "
                                       "mass to hold at the target",
                                       irreducible_now));
  return bare_now * target / irreducible_now;
}

}  // namespace bhnsid::puncture
