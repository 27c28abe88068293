#pragma once
// Surface integrals over the outer faces of the cube on the finest level: trapezoid weights along
// each face; with equatorial symmetry the stored half counts twice (the z = 0 edge at half weight).
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::diagnostics {

/// Calls fn(axis, sign, i, j, k, dA) for every point of every outer face: axis 0..2 and sign +-1 give
/// the outward normal sign e_axis; dA the point's trapezoid area weight (twice that of a stored
/// point with equatorial symmetry, which stands for its mirror image too).
template <class Fn>
void for_each_face_point(const Level& lv, Fn&& fn) {
  const int last[3] = {lv.nx - 1, lv.ny - 1, lv.nz - 1};
  const double mirror = lv.z_symmetry ? 2.0 : 1.0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      if (axis == 2 && side == 0 && lv.z_symmetry) continue;  // z = 0 is the symmetry plane, not a face
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      for (int ia = 0; ia <= last[a]; ++ia)
        for (int ib = 0; ib <= last[b]; ++ib) {
          int idx[3];
          idx[axis] = side == 0 ? 0 : last[axis], idx[a] = ia, idx[b] = ib;
          double w = lv.dx * lv.dx;
          w *= (ia == 0 || ia == last[a]) ? 0.5 : 1.0;
          w *= (ib == 0 || ib == last[b]) ? 0.5 : 1.0;
          // With symmetry every weight doubles: the z = 0 row (half weight as the stored range's
          // edge) then counts once, the others for themselves and their images, the top face for
          // the bottom one. The integrand must be even under the reflection, flux sign included.
          fn(axis, side == 0 ? -1.0 : 1.0, idx[0], idx[1], idx[2], w * mirror);
        }
    }
}

}  // namespace bhnsid::diagnostics
