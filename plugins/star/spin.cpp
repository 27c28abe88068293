#include "spin.hpp"

#include <memory>

namespace bhnsid::star {

Spin star_spin(Grid& grid, const StarFluid& fluid) {
  const Level& lv = grid.finest();
  fluid.update_sources(grid, 0);
  const auto lorentz = std::make_unique_for_overwrite<double[]>(lv.size);
  fluid.flow().velocity(grid, fluid.flow_constants(), lorentz.get(), nullptr);
  const double* rho0 = grid.data(grid.field_id(fields::rho0), 0, 0);
  const double* chi = grid.data(grid.field_id(fields::chi), 0, 0);
  const double* pphi = grid.data(grid.field_id(fields::puncture_phi), 0, 0);
  const int j = grid.field_id(fields::matter_momentum);
  const double *jx = grid.data(j, 0, 0), *jy = grid.data(j, 1, 0);
  // Every stored point is written (integrate reads no ghost).
  const auto mass = std::make_unique_for_overwrite<double[]>(lv.size), mass_x = std::make_unique_for_overwrite<double[]>(lv.size),
             mom = std::make_unique_for_overwrite<double[]>(lv.size), ang = std::make_unique_for_overwrite<double[]>(lv.size);
  double *m = mass.get(), *mx = mass_x.get(), *py = mom.get(), *jz = ang.get();
  const double* w = lorentz.get();
  for_stored_points_xy(lv, [&](std::ptrdiff_t p, double x, double y) {
    const double phi = pphi[p] + chi[p], phi2 = phi * phi, phi6 = phi2 * phi2 * phi2, phi10 = phi6 * phi2 * phi2;
    m[p] = rho0[p] > 0 ? rho0[p] * w[p] * phi6 : 0.0;
    mx[p] = x * m[p];
    py[p] = phi10 * jy[p];
    jz[p] = phi10 * (x * jy[p] - y * jx[p]);
  });
  // All four integrands are even in z (j^x, j^y even).
  const double s = fluid.sigma();
  Spin out;
  out.centroid_x = s * grid.integrate(mx, Parity{}, 0) / grid.integrate(m, Parity{}, 0);
  out.momentum_y = s * s * s * grid.integrate(py, Parity{}, 0);
  out.angular_momentum = s * s * s * s * grid.integrate(jz, Parity{}, 0);
  out.spin = out.angular_momentum - out.centroid_x * out.momentum_y;
  return out;
}

}  // namespace bhnsid::star
