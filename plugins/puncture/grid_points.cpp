#include "grid_points.hpp"

#include <fmt/format.h>

#include <cmath>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::puncture {

void check_off_the_points(const core::Context& ctx, const std::array<double, 3>& x) {
  const auto& grid = ctx.params("grid");
  const long n = grid.integer("n");
  const double dx = grid.real("dx"), half = 0.5 * static_cast<double>(n) * dx;
  for (int a = 0; a < 3; ++a)
    if (!(std::fabs(x[a]) < half))
      throw core::InputError(fmt::format("puncture.position = ({}, {}, {}): outside the cube |x_i| < {} (grid.n dx / 2)",
                                         x[0], x[1], x[2], half));
  // Vertex-centred levels coarsen by 2, so every coarse point is also a point of the finest level:
  // checking level 0 covers them all.
  int on_lines = 0;
  for (int a = 0; a < 3; ++a) {
    const double t = (x[a] + half) / dx;
    if (std::fabs(t - std::round(t)) < 1e-6) ++on_lines;
  }
  if (on_lines == 3)
    throw core::InputError(fmt::format(
        "puncture.position = ({}, {}, {}) is a grid point (grid.dx = {}): 1/r would be infinite there; move it off "
        "the points, e.g. by dx/2 = {} in x",
        x[0], x[1], x[2], dx, 0.5 * dx));
}

}  // namespace bhnsid::puncture
