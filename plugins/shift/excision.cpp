#include "excision.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace bhnsid::shift {

Cube excision_cube(double bare_mass, const std::array<double, 3>& position, double finest_dx, double min_side) {
  Cube c;
  c.centre = position;
  c.side = std::max({0.5 * bare_mass, 3.0 * finest_dx, min_side});
  c.half = 0.5 * c.side + 1e-12 * finest_dx;
  for (std::size_t a = 0; a < 3; ++a) {
    c.lo[a] = position[a] - c.half;
    c.hi[a] = position[a] + c.half;
  }
  return c;
}

void snap_to_lattice(Cube& cube, const Level& finest, double spacing) {
  const double slack = 1e-12 * finest.dx;
  for (std::size_t a = 0; a < 3; ++a) {
    const double o = finest.origin[a];
    cube.lo[a] = o + spacing * std::round((cube.centre[a] - 0.5 * cube.side - o) / spacing) - slack;
    cube.hi[a] = o + spacing * std::round((cube.centre[a] + 0.5 * cube.side - o) / spacing) + slack;
  }
}

namespace {

bool inside(const Cube& c, double x, double y, double z) {
  return c.lo[0] <= x && x <= c.hi[0] && c.lo[1] <= y && y <= c.hi[1] && c.lo[2] <= z && z <= c.hi[2];
}

int nearest_index(double coordinate, double origin, double dx, int lo, int hi) {
  const long index = std::lround((coordinate - origin) / dx);
  return static_cast<int>(std::clamp<long>(index, lo, hi));
}

}  // namespace

int build_mask(const Level& lv, const Cube& cube, std::uint8_t* bytes, bool& nearest) {
  std::memset(bytes, 0, lv.size);
  int count = 0;
  // Only the cube's bounding box (and its mirror image's under equatorial symmetry) can hold points.
  const auto [ri, rj, rk] = lv.indices_near_box(cube.lo, cube.hi);
  for (int k = rk[0]; k <= rk[1]; ++k)
    for (int j = rj[0]; j <= rj[1]; ++j)
      for (int i = ri[0]; i <= ri[1]; ++i) {
        const double x = lv.x(i), y = lv.y(j), z = lv.z(k);
        // Under equatorial symmetry the cube stands for itself and its mirror image (as Grid::add_mask).
        if (inside(cube, x, y, z) || (lv.z_symmetry && inside(cube, x, y, -z))) {
          bytes[lv.at(i, j, k)] = 1;
          ++count;
        }
      }
  nearest = count == 0;
  if (nearest) {
    // The level is too coarse for the cube: hold the interior point nearest the hole instead, so
    // that the coarse problem also has Dirichlet data there (physics-notes §4.6).
    const double zc = lv.z_symmetry ? std::fabs(cube.centre[2]) : cube.centre[2];
    const int i = nearest_index(cube.centre[0], lv.origin[0], lv.dx, 1, lv.nx - 2);
    const int j = nearest_index(cube.centre[1], lv.origin[1], lv.dx, 1, lv.ny - 2);
    const int k = nearest_index(zc, lv.origin[2], lv.dx, lv.k_begin(), lv.nz - 2);
    bytes[lv.at(i, j, k)] = 1;
    count = 1;
  }
  return count;
}

std::array<double, 3> excision_shift(const std::array<double, 3>& momentum, double bare_mass, ExcisionValue form) {
  const std::array<double, 3> v{momentum[0] / bare_mass, momentum[1] / bare_mass, momentum[2] / bare_mass};
  const double factor = form == ExcisionValue::lorentz ? 1.0 / std::sqrt(1.0 - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))
                                                       : 1.0;
  return {0.0 - factor * v[0], 0.0 - factor * v[1], 0.0 - factor * v[2]};  // 0 - x: no -0 in the log
}

std::string cube_outside_grid(const Cube& cube, const Level& finest) {
  const double rc = finest.half_width();
  const char* axes = "xyz";
  for (int a = 0; a < 3; ++a) {
    // With equatorial symmetry z = 0 is a symmetry plane, not a face: only |z| + s/2 matters there too.
    const double reach = std::fmax(std::fabs(cube.lo[static_cast<std::size_t>(a)]), std::fabs(cube.hi[static_cast<std::size_t>(a)]));
    if (reach >= rc)
      return fmt::format("the excision cube (side {:.6g} about xhat_BH = ({:.6g}, {:.6g}, {:.6g})) reaches {} = {:.6g}, "
                         "at or beyond the outer face at {:.6g}",
                         cube.side, cube.centre[0], cube.centre[1], cube.centre[2], axes[a], reach, rc);
  }
  return {};
}

}  // namespace bhnsid::shift
