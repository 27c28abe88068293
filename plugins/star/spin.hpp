#pragma once
// The star's own angular momentum about its rest-mass centroid (physical units):
//   J_spin = J_* - X_m P^y_*,  J_* = sigma^4 Int phi^10 (xhat j^y - yhat j^x),  P^y_* = sigma^3 Int phi^10 j^y,
//   X_m = sigma Int xhat rho0 W phi^6 / Int rho0 W phi^6,
// the orbital part cancelling exactly for a star that translates rigidly (j ∝ rho0 W phi^-4 times a
// constant p). About I Omega for a corotating star, about 0 for an irrotational one.
#include "bhnsid/interfaces/grid.hpp"
#include "fluid.hpp"

namespace bhnsid::star {

struct Spin {
  double spin = 0, centroid_x = 0, momentum_y = 0, angular_momentum = 0;
};

/// From the projections of the finest level (refreshed here) and the flow's W.
Spin star_spin(Grid& grid, const StarFluid& fluid);

}  // namespace bhnsid::star
