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

double surface_flux_mass(const Grid& grid, double sigma, double bare_mass_hat) {
  const Level& lv = grid.finest();
  const double* chi = grid.data(grid.field_id(fields::chi), 0, 0);
  const std::ptrdiff_t stride[3] = {lv.at(1, 0, 0) - lv.at(0, 0, 0), lv.at(0, 1, 0) - lv.at(0, 0, 0),
                                    lv.at(0, 0, 1) - lv.at(0, 0, 0)};
  double flux = 0;
  for_each_face_point(lv, [&](int axis, double sign, int i, int j, int k, double area) {
    const std::ptrdiff_t p = lv.at(i, j, k), in = -static_cast<std::ptrdiff_t>(sign) * stride[axis];
    // Outward derivative, one-sided: (3 f_0 - 4 f_1 + f_2) / (2 dx) with f_m m points inwards.
    const double dn = (3.0 * chi[p] - 4.0 * chi[p + in] + chi[p + 2 * in]) / (2.0 * lv.dx);
    flux += dn * area;
  });
  return sigma * (bare_mass_hat - flux / (2.0 * std::numbers::pi));
}

OutsideMass outside_aa_mass(const Grid& grid, double sigma, const std::array<double, 3>& centre,
                            const std::array<double, 2>& net_momentum_hat) {
  const Level& lv = grid.finest();
  const double* aa = grid.data(grid.field_id(fields::aa), 0, 0);
  const double pn2 = net_momentum_hat[0] * net_momentum_hat[0] + net_momentum_hat[1] * net_momentum_hat[1];
  double net = 0, rest = 0;
  for_each_face_point(lv, [&](int axis, double sign, int i, int j, int k, double area) {
    const double d[3] = {lv.x(i) - centre[0], lv.y(j) - centre[1], lv.z(k) - centre[2]};
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    // The Bowen-York AA of the net momentum about the centre, 9 P^2 (1 + 2 cos^2 theta) / (2 r^4)
    // (physics-notes §2.6), cos theta the angle between the point and P.
    const double pd = net_momentum_hat[0] * d[0] + net_momentum_hat[1] * d[1];
    const double cos2 = pn2 > 0 ? pd * pd / (pn2 * r2) : 0.0;
    const double aa_net = 4.5 * pn2 * (1.0 + 2.0 * cos2) / (r2 * r2);
    const double flux = d[axis] * sign * area;
    net += aa_net * flux;
    rest += (aa[lv.at(i, j, k)] - aa_net) * flux;
  });
  const double c = sigma / (16.0 * std::numbers::pi);
  // A part falling like r^-p leaves Int_face^inf r^(2-p) dr = r_face^(3-p)/(p-3) outside: p = 4 for
  // the net momentum's, p = 6 for the rest (Ahat ~ r^-3 once the momenta cancel).
  return {c * net, c * rest / 3.0};
}

}  // namespace bhnsid::diagnostics
