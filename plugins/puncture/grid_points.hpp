#pragma once
// The check that keeps the puncture off every grid point: 1/r there would be infinite.
#include <array>

#include "bhnsid/core/context.hpp"

namespace bhnsid::puncture {

/// Throws core::InputError naming puncture.position when it lies within 1e-6 dx of a point of the
/// grid that grid.n, grid.dx describe (of any of its levels), or outside the cube.
void check_off_the_points(const core::Context& ctx, const std::array<double, 3>& x);

}  // namespace bhnsid::puncture
