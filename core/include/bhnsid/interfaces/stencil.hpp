#pragma once
// Loop scaffolding shared by equation kernels: OpenMP over planes, plain loops over rows and
// points that the compiler vectorises. Header-only so that every call inlines into the plugin's
// kernel; no virtual call below the level of a whole sweep.
#include <omp.h>

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::stencil {

/// A loop over fewer points than this runs on one thread: on the coarsest levels (n = 4, 8: 18
/// and 200 interior points) the wake-up and barrier of a parallel region cost more than the loop,
/// and the coarsest level's Jacobian alone evaluates the residual of every equation 600 times.
constexpr long parallel_min_points = 1024;

/// Interior points of a level.
inline long interior_points(const Level& lv) {
  return static_cast<long>(lv.nx - 2) * (lv.ny - 2) * (lv.nz - 1 - lv.k_begin());
}

/// Calls row(j, k) for every interior row of the level, planes distributed over OpenMP threads.
/// The row's interior points are i = 1 .. nx-2.
template <class RowFn>
inline void for_interior_rows(const Level& lv, RowFn&& row) {
  const int k0 = lv.k_begin(), k1 = lv.nz - 1, j1 = lv.ny - 1;
#pragma omp parallel for schedule(static) if (interior_points(lv) >= parallel_min_points)
  for (int k = k0; k < k1; ++k)
    for (int j = 1; j < j1; ++j) row(j, k);
}

/// Whether any interior point i in [1, end) of a row is held (mask != 0). The sweeps run a row
/// without held points through the unmasked loop: GCC 12 does not vectorise a loop that reads the
/// byte mask (at stride 2 in the red-black sweeps), and held points (an excision region) lie in a
/// few rows only, so the test keeps almost every row vectorised.
inline bool row_has_fixed(const std::uint8_t* m, int end) {
  unsigned any = 0;
  for (int i = 1; i < end; ++i) any |= m[i];
  return any != 0;
}

/// Calls row(std::true_type{}) when the row [p, p + end) holds a fixed point, row(std::false_type{})
/// otherwise (always when Masked is false, without reading the mask).
template <bool Masked, class RowFn>
[[gnu::always_inline]] inline void with_row_mask(const std::uint8_t* fixed, std::ptrdiff_t p, int end, RowFn&& row) {
  if constexpr (Masked) {
    if (row_has_fixed(fixed + p, end)) {
      row(std::true_type{});
      return;
    }
  }
  row(std::false_type{});
}

/// First interior i of a row whose points have (i + j + k) % 2 == colour; step 2 from there.
inline int first_of_colour(int j, int k, int colour) { return 1 + ((1 + j + k + colour) & 1); }

/// One red-black Gauss-Seidel sweep, both colours fused plane by plane: colour 0 on plane k, then
/// colour 1 on plane k-1, so that the fields stream through memory once per sweep instead of twice.
/// The result is exactly that of all colour-0 points followed by all colour-1 points, since points
/// of one colour read only the other's. Threads own slabs of planes; each first relaxes colour 0
/// on both of its end planes, then (after a barrier) runs the wavefront inside its slab, so no
/// thread reads a neighbour's plane before it is final.
///   plane(k, colour): relax every interior row of plane k for that colour;
///   mirror():         with z symmetry, refresh the ghost plane k = -1 from plane 1; called after
///                     colour 0 on plane 1 and before colour 1 on plane 0.
/// Levels too thin to give every thread 4 planes run the two colours as two plain passes.
/// Only for stencils whose points of one colour read none of their own colour (7-point and
/// other axis-only stencils): a mixed derivative reads diagonal neighbours, which share the
/// colour, and the wavefront would race at slab boundaries (mms's vector kernel shows the
/// alternative: each colour as two passes, even planes then odd). mirror() runs on one thread
/// inside the parallel region; a decomposed grid whose ghost fill communicates needs another way.
template <class PlaneFn, class MirrorFn>
inline void red_black_sweep(const Level& lv, PlaneFn&& plane, MirrorFn&& mirror) {
  const int k0 = lv.k_begin(), k1 = lv.nz - 1, planes = k1 - k0;
  const int threads = omp_get_max_threads();
  if (planes < 4 * threads) {
    const bool parallel = interior_points(lv) / 2 >= parallel_min_points;
    for (int colour = 0; colour < 2; ++colour) {
#pragma omp parallel for schedule(static) if (parallel)
      for (int k = k0; k < k1; ++k) plane(k, colour);
      if (colour == 0 && lv.z_symmetry) mirror();
    }
    return;
  }
#pragma omp parallel
  {
    const int nt = omp_get_num_threads(), t = omp_get_thread_num();
    const int a = k0 + static_cast<int>(static_cast<long>(planes) * t / nt);
    const int b = k0 + static_cast<int>(static_cast<long>(planes) * (t + 1) / nt);
    plane(a, 0);
    plane(b - 1, 0);
#pragma omp barrier
    for (int k = a + 1; k < b - 1; ++k) {
      plane(k, 0);
      if (k == 1 && lv.z_symmetry) mirror();
      plane(k - 1, 1);
    }
    plane(b - 2, 1);
    plane(b - 1, 1);
  }
}

/// Inverse squared spacing, the factor of every second-difference stencil.
inline double inv_h2(const Level& lv) { return 1.0 / (lv.dx * lv.dx); }

}  // namespace bhnsid::stencil
