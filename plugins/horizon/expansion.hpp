#pragma once
// The outgoing expansion of a surface r = h(theta, phi) about the puncture in a conformally flat
// slice with K = 0, gamma_ij = phi^4 delta_ij, K_ij = phi^-2 Ahat_ij (hatted units):
//   Theta = phi^-2 (d_i s^i + 4 s^i d_i ln phi) + phi^-6 Ahat_ij s^i s^j,
// s the flat unit normal of F = r - h(theta, phi). The horizon finder zeroes phi^2 Theta (the same
// surface, better scaled). The derivatives of h come from the harmonics' own (tabulated at the
// collocation points), the Cartesian ones of theta and phi analytically, so no surface is
// differenced in space.
#include <array>
#include <vector>

#include "local_fields.hpp"
#include "surface.hpp"

namespace bhnsid::horizon {

/// The harmonics and their angular derivatives at every collocation point.
struct SurfaceTables {
  explicit SurfaceTables(const SurfaceBasis& basis);
  const SurfaceBasis& basis;
  /// [point][mode]: Y, Y_theta, Y_phi, Y_theta_theta, Y_theta_phi, Y_phi_phi.
  std::vector<std::array<double, 6>> y;
  std::size_t modes = 0;
  const std::array<double, 6>& at(std::size_t point, std::size_t mode) const { return y[point * modes + mode]; }
};

/// One collocation point of the surface with coefficients a.
struct SurfaceGeometry {
  std::array<double, 3> x{};        ///< the surface point (hatted)
  std::array<double, 3> normal{};   ///< s, the flat unit normal (outward)
  double divergence = 0;            ///< d_i s^i (flat)
  double h = 0;                     ///< r of the point
  double area = 0;                  ///< flat area element times the quadrature weight
};

SurfaceGeometry geometry(const SurfaceTables& t, const std::vector<double>& a, std::size_t point,
                         const std::array<double, 3>& centre);

/// phi^2 Theta at a surface point.
double scaled_expansion(const SurfaceGeometry& g, const FieldPoint& f);

}  // namespace bhnsid::horizon
