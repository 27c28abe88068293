#pragma once
// The excision cube about the puncture and the shift held there (physics-notes §4.6): full side
// s = max(Mhat_BH/2, 3 dx) (dx of the finest level), points with max_i |x^i - xhat_BH^i| <= s/2
// (+1e-12 dx) excised on every level; on a level where the cube holds no point the interior point
// nearest xhat_BH is excised instead, so that every level has Dirichlet data. The excised points hold
// beta_0 = -v/sqrt(1 - |v|^2) (the paper's form) or -v, with v = Phat_BH/Mhat_BH.
#include <array>
#include <cstdint>
#include <string>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::shift {

enum class ExcisionValue { lorentz, plain };

/// The cube: centre xhat_BH, full side s, the half size s/2 + 1e-12 dx, and the bounds of the
/// inside test per axis, lo <= x <= hi (centre -+ half, or the lattice planes of snap_to_lattice).
struct Cube {
  std::array<double, 3> centre{};
  double side = 0;
  double half = 0;
  std::array<double, 3> lo{}, hi{};
};

/// s = max(Mhat/2, 3 dx, min_side), half = s/2 + 1e-12 dx, bounds centre -+ half.
Cube excision_cube(double bare_mass, const std::array<double, 3>& position, double finest_dx, double min_side = 0);

/// Moves each face of the cube to the nearest plane of the lattice origin + m D (D = dx 2^p, checked
/// by the caller). A staircase cube whose faces fall between grid points excises a slightly
/// different region at every dx: a Dirichlet boundary displaced by O(dx), which makes the shift
/// converge at first order. The lattice planes are grid planes at dx, dx/2, dx/4, ... with the
/// same cube of the grid, so a convergence series with one D excises exactly the same region. Each
/// face moves by at most D/2.
void snap_to_lattice(Cube& cube, const Level& finest, double spacing);

/// Writes the mask of one level into `bytes` (Level::size bytes; 1 excised, 0 elsewhere and on the
/// ghosts): the points inside the cube (with equatorial symmetry also those whose mirror image is),
/// or, when there are none, the interior point nearest the centre. Returns the number of stored
/// points set; `nearest` tells whether the fallback was used.
int build_mask(const Level& lv, const Cube& cube, std::uint8_t* bytes, bool& nearest);

/// beta_0 from the hole's momentum and bare mass (> 0); with the lorentz form |v| < 1 is required
/// (the caller checks both and reports them against the parameters).
std::array<double, 3> excision_shift(const std::array<double, 3>& momentum, double bare_mass, ExcisionValue form);

/// Empty when the cube lies inside the cube of the grid (no excised point on an outer face),
/// otherwise a description of where it reaches the outer boundary.
std::string cube_outside_grid(const Cube& cube, const Level& finest);

}  // namespace bhnsid::shift
