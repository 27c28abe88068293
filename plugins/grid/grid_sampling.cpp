// Reading a field out of the grid: volume integrals, values at arbitrary points, the x axis.
#include <fmt/format.h>

#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "uniform_grid.hpp"

namespace bhnsid::grid {

double UniformGrid::integrate(const double* values, Parity parity, int level_index) const {
  const Level& lv = level(level_index);
  // An odd field integrates to zero over the full cube; its stored half says nothing more.
  if (lv.z_symmetry && parity.z < 0) return 0.0;
  auto weight = [](int i, int last) { return (i == 0 || i == last) ? 0.5 : 1.0; };
  double sum = 0;
#pragma omp parallel for reduction(+ : sum) schedule(static)
  for (int k = 0; k < lv.nz; ++k) {
    const double wk = weight(k, lv.nz - 1);
    double plane = 0;
    for (int j = 0; j < lv.ny; ++j) {
      const double* row = values + lv.at(0, j, k);
      double line = 0.5 * (row[0] + row[lv.nx - 1]);
      for (int i = 1; i < lv.nx - 1; ++i) line += row[i];
      plane += weight(j, lv.ny - 1) * line;
    }
    sum += wk * plane;
  }
  // With equatorial symmetry the trapezoid weight 1/2 on z = 0 and the factor 2 together count
  // the plane once and each stored half-plane twice.
  const double volume = lv.dx * lv.dx * lv.dx * (lv.z_symmetry ? 2.0 : 1.0);
  return global_sum(sum * volume);
}

namespace {

// Nodes first .. first+3 and their Lagrange weights at fractional index t.
struct Stencil4 {
  int first;
  double w[4];
};

Stencil4 stencil4(double t, int lowest, int last_point) {
  Stencil4 s;
  s.first = static_cast<int>(std::floor(t)) - 1;
  if (s.first < lowest) s.first = lowest;
  if (s.first > last_point - 3) s.first = last_point - 3;
  for (int a = 0; a < 4; ++a) {
    double w = 1;
    for (int b = 0; b < 4; ++b)
      if (b != a) w *= (t - (s.first + b)) / static_cast<double>(a - b);
    s.w[a] = w;
  }
  return s;
}

}  // namespace

double UniformGrid::interpolate(const double* values, Parity parity, int level_index,
                                std::array<double, 3> point) const {
  const Level& lv = level(level_index);
  const double r = lv.half_width() * (1 + 1e-12);
  for (int a = 0; a < 3; ++a)
    if (!(std::fabs(point[a]) <= r))
      throw core::RunFailure(fmt::format("grid: cannot interpolate at ({}, {}, {}): outside the cube |x_i| <= {}",
                                         point[0], point[1], point[2], lv.half_width()));
  if (lv.nx < 4) throw core::RunFailure("grid: interpolation needs at least 4 points per axis");
  double zsign = 1;
  double pz = point[2];
  if (lv.z_symmetry && pz < 0) {  // the image point, with the field's parity
    pz = -pz;
    zsign = parity.z;
  }
  const Stencil4 sx = stencil4((point[0] - lv.origin[0]) / lv.dx, 0, lv.nx - 1);
  const Stencil4 sy = stencil4((point[1] - lv.origin[1]) / lv.dx, 0, lv.ny - 1);
  // Near the symmetry plane the stencil reaches below it, into mirror images.
  const Stencil4 sz = stencil4((pz - lv.origin[2]) / lv.dx, lv.z_symmetry ? -2 : 0, lv.nz - 1);
  double result = 0;
  for (int c = 0; c < 4; ++c) {
    const int k = sz.first + c;
    const double image = k < 0 ? parity.z : 1.0;
    double plane = 0;
    for (int b = 0; b < 4; ++b) {
      const double* row = values + lv.at(0, sy.first + b, k < 0 ? -k : k);
      double line = 0;
      for (int a = 0; a < 4; ++a) line += sx.w[a] * row[sx.first + a];
      plane += sy.w[b] * line;
    }
    result += sz.w[c] * image * plane;
  }
  return zsign * result;
}

std::vector<std::array<double, 2>> UniformGrid::line_x(const double* values, int level_index) const {
  const Level& lv = level(level_index);
  if (lv.n % 2 != 0)
    throw core::RunFailure(fmt::format("grid: level {} has an odd number of intervals; the x axis is not a grid line",
                                       level_index));
  const int j = lv.n / 2, k = lv.z_symmetry ? 0 : lv.n / 2;
  std::vector<std::array<double, 2>> line;
  line.reserve(static_cast<std::size_t>(lv.nx));
  for (int i = 0; i < lv.nx; ++i) line.push_back({lv.x(i), values[lv.at(i, j, k)]});
  return line;
}

}  // namespace bhnsid::grid
