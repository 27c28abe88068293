#pragma once
// Loop scaffolding shared by equation kernels: OpenMP over planes, plain loops over rows and
// points that the compiler vectorises. Header-only so that every call inlines into the plugin's
// kernel; no virtual call below the level of a whole sweep.
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::stencil {

/// Calls row(j, k) for every interior row of the level, planes distributed over OpenMP threads.
/// The row's interior points are i = 1 .. nx-2.
template <class RowFn>
inline void for_interior_rows(const Level& lv, RowFn&& row) {
  const int k0 = lv.k_begin(), k1 = lv.nz - 1, j1 = lv.ny - 1;
#pragma omp parallel for schedule(static)
  for (int k = k0; k < k1; ++k)
    for (int j = 1; j < j1; ++j) row(j, k);
}

/// First interior i of a row whose points have (i + j + k) % 2 == colour; step 2 from there.
inline int first_of_colour(int j, int k, int colour) { return 1 + ((1 + j + k + colour) & 1); }

/// Inverse squared spacing, the factor of every second-difference stencil.
inline double inv_h2(const Level& lv) { return 1.0 / (lv.dx * lv.dx); }

}  // namespace bhnsid::stencil
