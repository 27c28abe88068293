#pragma once
// The level hierarchy: vertex-centred cubes of n intervals about the origin. With nested boxes the
// finest `boxes` levels are cubes of n intervals each, every one twice as wide as the one inside
// it; the outermost box is then coarsened by 2 while that keeps every level a grid of the same
// cube with the origin and the symmetry plane on grid points.
#include <vector>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::grid {

struct HierarchySpec {
  int n = 0;
  double dx = 0;
  Symmetry symmetry = Symmetry::none;
  int max_levels = 0;        ///< 0: as many as the coarsening rule allows
  int min_coarse_intervals = 4;
  int boxes = 1;             ///< nested boxes, finest included (1: a single cube)
};

/// Throws core::InputError naming the grid parameter when n cannot make a grid.
std::vector<Level> build_hierarchy(const HierarchySpec& spec);

/// Level with n intervals and spacing dx, its memory layout included.
Level make_level(int index, int n, double dx, Symmetry symmetry);

}  // namespace bhnsid::grid
