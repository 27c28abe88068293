#pragma once
// Level 0 of a cube of n intervals of spacing dx, laid out as plugins/grid builds it (vertex-centred,
// one ghost layer, x contiguous), for kernel tests that run without a grid plugin.
#include <cstddef>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::test {

inline Level make_level(int n, double dx, bool z_symmetry) {
  Level lv;
  lv.index = 0;
  lv.n = n;
  lv.dx = dx;
  lv.z_symmetry = z_symmetry;
  lv.nx = lv.ny = n + 1;
  lv.nz = z_symmetry ? n / 2 + 1 : n + 1;
  const double h = 0.5 * n * dx;
  lv.origin = {-h, -h, z_symmetry ? 0.0 : -h};
  lv.sy = lv.nx + 2;
  lv.sz = lv.sy * (lv.ny + 2);
  lv.offset = 1 + lv.sy + lv.sz;
  lv.size = static_cast<std::size_t>(lv.sz) * static_cast<std::size_t>(lv.nz + 2);
  return lv;
}

}  // namespace bhnsid::test
