#pragma once
// The independent residual evaluator (physics-notes §7): from a solution (chi, alpha, beta, W and
// the ansatz weight q, the puncture, the fluid) it builds the physical fields gamma_ij, K_ij, alpha, beta^i and the matter in
// hatted coordinates and evaluates the covariant equations with generic Christoffel symbols, Ricci
// tensor and covariant derivatives, by centred differences of its own: first derivatives D0, second
// derivatives D0(D0 u) (the solver uses D+D-). It shares no code with the equation plugins;
// the matter projections it reads are the star's (refreshed from the solution).
#include <array>
#include <map>
#include <string>
#include <vector>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::ire {

struct Inputs {
  double sigma = 1;
  bool fluid = false;       ///< rho0, press, enthalpy and the matter projections present and meaningful
  double bernoulli = 0;     ///< C_B; NaN when the fluid has none (no Bernoulli residual)
  double omega_hat = 0;     ///< Omegahat of the helical symmetry (B = beta + Omegahat xi)
  /// The flow's first integral at every finest-level point (Flow::first_integral; C_B at a solution
  /// where rho0 > 0): the Bernoulli residual is its difference from C_B. Null: no Bernoulli residual.
  const double* first_integral = nullptr;
  /// W and v^i of the flow on the finest level (Flow::velocity), for the continuity residual
  /// d_i[rho0 W phi^6 (alpha v^i - B^i)]; null: the flow's kinematics make that flux vanish identically.
  const double* lorentz = nullptr;
  const double* velocity[3] = {nullptr, nullptr, nullptr};
  bool puncture = false;
  double bare_mass = 0;
  std::array<double, 3> position{}, momentum{};
  int exclude_cells = 2;    ///< the puncture's region: excision cube (or its rule) widened by this
  int surface_cells = 2;    ///< the star's surface band: points this close to a rho0 > 0 / = 0 change
  int stride = 1;           ///< residuals at every stride-th point per axis (the points of a coarser grid)
};

struct Norms {
  double l2 = 0, max = 0;
  long points = 0;
};

/// Residual norms per equation and region, and the x-axis table.
struct Result {
  std::vector<std::string> equations;           ///< hamiltonian, momentum, lapse, shift, bernoulli, continuity
  /// away: in vacuum, away from the puncture and the star's surface band; star: inside the star away
  /// from its band (for Bernoulli and continuity, away is the star's interior and star is empty).
  std::map<std::string, Norms> away, surface, puncture, star;
  std::string axis_table;                       ///< ire_axis.tsv
};

/// The residuals on the finest level of `grid`: at every point whose stencils (two points each
/// way) fit inside the cube; below z = 0 by symmetry.
Result evaluate(const Grid& grid, const Inputs& in);

}  // namespace bhnsid::ire
