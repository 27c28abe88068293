#include "surface.hpp"

#include <numbers>

#include "bhnsid/interfaces/spacetime.hpp"
#include "faces.hpp"

namespace bhnsid::diagnostics {

SurfaceMomenta surface_momenta(const Grid& grid, double sigma) {
  const Level& lv = grid.finest();
  const int ahat = grid.field_id(fields::ahat);
  const double* a[6];
  for (int c = 0; c < 6; ++c) a[c] = grid.data(ahat, c, 0);
  double px = 0, py = 0, jz = 0;
  for_each_face_point(lv, [&](int axis, double sign, int i, int j, int k, double area) {
    const std::ptrdiff_t p = lv.at(i, j, k);
    const double flux_x = a[sym_index(0, axis)][p] * sign * area;  // Ahat^{x n} dS
    const double flux_y = a[sym_index(1, axis)][p] * sign * area;
    px += flux_x;
    py += flux_y;
    jz += lv.x(i) * flux_y - lv.y(j) * flux_x;
  });
  const double c = 1.0 / (8.0 * std::numbers::pi);
  // With equatorial symmetry P^x's integrand is even too; only P^z's is odd (and P^z = 0).
  return {sigma * c * px, sigma * c * py, sigma * sigma * c * jz};
}

double outside_aa_mass(const Grid& grid, double sigma, const std::array<double, 3>& centre) {
  const Level& lv = grid.finest();
  const double* aa = grid.data(grid.field_id(fields::aa), 0, 0);
  double sum = 0;
  for_each_face_point(lv, [&](int axis, double sign, int i, int j, int k, double area) {
    const double x[3] = {lv.x(i), lv.y(j), lv.z(k)};
    sum += aa[lv.at(i, j, k)] * (x[axis] - centre[static_cast<std::size_t>(axis)]) * sign * area;
  });
  return sigma * sum / (16.0 * std::numbers::pi);
}

}  // namespace bhnsid::diagnostics
