#pragma once
// The apparent horizon about the puncture: Gauss-Newton on the harmonic coefficients of r = h(theta,
// phi) for phi^2 Theta = 0 at the collocation points (more points than coefficients; the Jacobian
// by differences of whole residuals), from a sphere. Then the area, the irreducible mass, the
// coordinate radii and the quasi-local spin with the flat rotational vector about z.
#include <string>
#include <vector>

#include "local_fields.hpp"
#include "surface.hpp"

namespace bhnsid::horizon {

struct FinderSettings {
  int l_max = 8;
  bool equatorial = true;
  double initial_radius = 0;  ///< hatted; 0: Mhat_BH/2, the Schwarzschild value
  double tolerance = 1e-10;   ///< largest Newton step, relative to the mean radius
  int max_iterations = 40;
  std::vector<double> start;  ///< coefficients to start from (the last horizon); empty: the sphere
};

struct Horizon {
  bool found = false;
  std::string failure;        ///< why not, when not found
  int iterations = 0;
  double residual = 0;        ///< max |phi^2 Theta| times the mean radius at the last iterate
  double area_hat = 0;        ///< sum phi^4 dA (hatted)
  double radius_min = 0, radius_max = 0, radius_mean = 0;  ///< hatted coordinate radii about the puncture
  double spin_hat = 0;        ///< (1/8 pi) sum Ahat_ij phi^i s^j dA, phi^i = z x (x - xhat_BH) (hatted)
  std::vector<double> coefficients;
  /// The l = 1 part of h: h ~ h0 + d.n + (l >= 2), d = this (hatted).
  std::array<double, 3> offset{};
};

Horizon find_horizon(const LocalFields& fields, const SurfaceBasis& basis, const FinderSettings& settings);

}  // namespace bhnsid::horizon
