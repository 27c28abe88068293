#include "binary.hpp"

#include <memory>

#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::diagnostics {

double matter_angular_momentum(const Grid& grid, double sigma) {
  const Level& lv = grid.finest();
  const double* chi = grid.data(grid.field_id(fields::chi), 0, 0);
  const double* punc = grid.has_field(fields::puncture_phi) ? grid.data(grid.field_id(fields::puncture_phi), 0, 0) : nullptr;
  const int j = grid.field_id(fields::matter_momentum);
  const double *jx = grid.data(j, 0, 0), *jy = grid.data(j, 1, 0);
  const auto density = std::make_unique_for_overwrite<double[]>(lv.size);  // integrate reads no ghost
  double* d = density.get();
  for_stored_points_xy(lv, [&](std::ptrdiff_t p, double x, double y) {
    const double phi = (punc ? punc[p] : 0.0) + chi[p], phi2 = phi * phi, phi4 = phi2 * phi2;
    d[p] = phi4 * phi4 * phi2 * (x * jy[p] - y * jx[p]);
  });
  const double s2 = sigma * sigma;
  // x j^y - y j^x is even under z -> -z (j^x, j^y even, physics-notes §8).
  return s2 * s2 * grid.integrate(d, Parity{}, 0);
}

}  // namespace bhnsid::diagnostics
