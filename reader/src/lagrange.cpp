#include "lagrange.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bhnsid_reader.h"

namespace bhnsid::reader {

namespace {

// A point this close to the box (in units of dx) is inside: coordinates computed as
// origin + i dx round either way.
constexpr double edge_tolerance = 1e-9;

std::string point_text(std::size_t index, double x, double y, double z) {
  std::ostringstream s;
  s.precision(17);
  s << "point " << index << " (" << x << ", " << y << ", " << z << ")";
  return s.str();
}

}  // namespace

void check_options(const Grid& g, const Options& o) {
  if (o.order < 2 || o.order > max_order || o.order % 2 != 0)
    throw Error(BHNSID_READER_ERR_ARGUMENT,
                "interpolation order " + std::to_string(o.order) + " is not supported (2, 4, 6 or 8 points per axis)");
  if (o.out_of_grid != BHNSID_READER_OUTSIDE_ERROR && o.out_of_grid != BHNSID_READER_OUTSIDE_CLAMP &&
      o.out_of_grid != BHNSID_READER_OUTSIDE_EXTRAPOLATE)
    throw Error(BHNSID_READER_ERR_ARGUMENT, "unknown out-of-grid policy " + std::to_string(o.out_of_grid));
  const int counts[3] = {g.nx, g.ny, g.nz - g.kmin()};
  const char* axes = "xyz";
  for (int a = 0; a < 3; ++a)
    if (counts[a] < o.order)
      throw Error(BHNSID_READER_ERR_ARGUMENT, "the grid has " + std::to_string(counts[a]) + " points along " + axes[a] +
                                                  ", fewer than interpolation order " + std::to_string(o.order) + " needs");
}

Stencil stencil_at(const Grid& g, const Options& o, double x, double y, double z, std::size_t index) {
  Stencil s;
  s.order = o.order;
  const double coord[3] = {x, y, z};
  const int first[3] = {0, 0, g.kmin()};
  const int last[3] = {g.nx - 1, g.ny - 1, g.nz - 1};
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(coord[a]))
      throw Error(BHNSID_READER_ERR_ARGUMENT, point_text(index, x, y, z) + " is not finite");
    double t = (coord[a] - g.origin[static_cast<std::size_t>(a)]) / g.dx;
    const bool outside = t < first[a] - edge_tolerance || t > last[a] + edge_tolerance;
    if (outside && o.out_of_grid == BHNSID_READER_OUTSIDE_ERROR) {
      std::ostringstream m;
      m.precision(17);
      m << point_text(index, x, y, z) << " is outside the grid: " << "xyz"[a] << " must lie in ["
        << g.origin[static_cast<std::size_t>(a)] + g.dx * first[a] << ", "
        << g.origin[static_cast<std::size_t>(a)] + g.dx * last[a] << "]";
      throw Error(BHNSID_READER_ERR_OUTSIDE, m.str());
    }
    s.point[static_cast<std::size_t>(a)] = coord[a];
    if (outside && o.out_of_grid == BHNSID_READER_OUTSIDE_EXTRAPOLATE) s.extrapolated = true;
    if (!outside || o.out_of_grid == BHNSID_READER_OUTSIDE_CLAMP) {
      const double clamped = std::clamp(t, double(first[a]), double(last[a]));
      if (clamped != t) s.point[static_cast<std::size_t>(a)] = g.origin[static_cast<std::size_t>(a)] + g.dx * clamped;
      t = clamped;
    }
    // Clamped as a double first: an extrapolated t of 1e300 must not overflow the conversion.
    const double cell = std::clamp(std::floor(t), double(first[a] - o.order), double(last[a] + o.order));
    int start = static_cast<int>(cell) - (o.order / 2 - 1);
    start = std::clamp(start, first[a], last[a] - o.order + 1);
    s.start[static_cast<std::size_t>(a)] = start;
    const double u = t - start;  // the point in the stencil's own coordinate, nodes at 0 .. order-1
    for (int j = 0; j < o.order; ++j) {
      double num = 1, den = 1;
      for (int m = 0; m < o.order; ++m)
        if (m != j) {
          num *= u - m;
          den *= j - m;
        }
      s.w[static_cast<std::size_t>(a)][static_cast<std::size_t>(j)] = num / den;
    }
  }
  return s;
}

double interpolate(const Grid& g, const Field& f, const Stencil& s) {
  const int p = s.order;
  const auto& wx = s.w[0];
  const auto& wy = s.w[1];
  const auto& wz = s.w[2];
  double total = 0;
  for (int c = 0; c < p; ++c) {
    const int k = s.start[2] + c;
    const double sign = k < 0 ? f.parity : 1.0;
    const int kk = k < 0 ? -k : k;
    double sy = 0;
    for (int b = 0; b < p; ++b) {
      const double* row = f.values.data() + g.at(s.start[0], s.start[1] + b, kk);
      double sx = 0;
      for (int a = 0; a < p; ++a) sx += wx[static_cast<std::size_t>(a)] * row[a];
      sy += wy[static_cast<std::size_t>(b)] * sx;
    }
    total += wz[static_cast<std::size_t>(c)] * (sign * sy);
  }
  return total;
}

}  // namespace bhnsid::reader
