#include "hierarchy.hpp"

#include <fmt/format.h>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::grid {

Level make_level(int index, int n, double dx, Symmetry symmetry) {
  Level lv;
  lv.index = index;
  lv.n = n;
  lv.dx = dx;
  lv.z_symmetry = symmetry == Symmetry::equatorial;
  lv.nx = lv.ny = n + 1;
  lv.nz = lv.z_symmetry ? n / 2 + 1 : n + 1;
  const double h = 0.5 * n * dx;
  lv.origin = {-h, -h, lv.z_symmetry ? 0.0 : -h};
  lv.sy = lv.nx + 2;
  lv.sz = lv.sy * (lv.ny + 2);
  lv.offset = 1 + lv.sy + lv.sz;
  lv.size = static_cast<std::size_t>(lv.sz) * static_cast<std::size_t>(lv.nz + 2);
  return lv;
}

std::vector<Level> build_hierarchy(const HierarchySpec& spec) {
  if (spec.n < 2 || spec.n % 2 != 0)
    throw core::InputError(fmt::format(
        "grid.n = {}: expected an even number of intervals >= 2, so that the origin and the axes are grid points",
        spec.n));
  if (spec.boxes > 1 && spec.n % 4 != 0)
    throw core::InputError(fmt::format(
        "grid.n = {} with grid.boxes = {}: expected n divisible by 4, so that each box's faces (and, with "
        "equatorial symmetry, its top) lie on points of the box about it",
        spec.n, spec.boxes));
  if (spec.max_levels > 0 && spec.max_levels < spec.boxes)
    throw core::InputError(fmt::format("grid.max_levels = {} is below grid.boxes = {}: every box is a level",
                                       spec.max_levels, spec.boxes));
  std::vector<Level> levels{make_level(0, spec.n, spec.dx, spec.symmetry)};
  for (int box = 1; box < spec.boxes; ++box) {
    levels.back().inner = true;
    levels.push_back(make_level(box, spec.n, 2 * levels.back().dx, spec.symmetry));
  }
  for (;;) {
    const Level& fine = levels.back();
    if (spec.max_levels > 0 && static_cast<int>(levels.size()) >= spec.max_levels) break;
    // Every coarse point must be a fine point (n even), and with equatorial symmetry the coarse
    // level needs n/2 whole intervals above the z = 0 plane (n even again).
    const int nc = fine.n / 2;
    const bool eq = spec.symmetry == Symmetry::equatorial;
    if (fine.n % 2 != 0 || nc < spec.min_coarse_intervals || (eq && nc % 2 != 0)) break;
    levels.push_back(make_level(static_cast<int>(levels.size()), nc, 2 * fine.dx, spec.symmetry));
  }
  return levels;
}

}  // namespace bhnsid::grid
