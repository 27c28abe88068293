#include "boundary_rows.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::multigrid {

std::vector<RayStencil> robin_stencils(const Level& lv, const std::array<double, 3>& centre) {
  std::vector<RayStencil> rows;
  const int last[3] = {lv.nx - 1, lv.ny - 1, lv.nz - 1};
  for_face_points(lv, [&](int i, int j, int k) {
    const double xb[3] = {lv.x(i), lv.y(j), lv.z(k)};
    double X[3], reach = 0;
    for (int a = 0; a < 3; ++a) {
      X[a] = xb[a] - centre[a];
      reach = std::max(reach, std::fabs(X[a]));
    }
    if (reach < 2 * lv.dx)
      throw core::RunFailure(fmt::format(
          "multigrid: the Robin centre ({}, {}, {}) is within 2 cells of the face point ({}, {}, {}) on level {}",
          centre[0], centre[1], centre[2], xb[0], xb[1], xb[2], lv.index));
    RayStencil row;
    row.point = lv.at(i, j, k);
    row.scale = 1.0 - lv.dx / reach;
    int cell[3];
    double frac[3];
    for (int a = 0; a < 3; ++a) {
      const double t = (centre[a] + row.scale * X[a] - lv.origin[a]) / lv.dx;
      int m = static_cast<int>(std::floor(t));
      m = std::clamp(m, 0, last[a] - 1);
      cell[a] = m;
      frac[a] = std::clamp(t - m, 0.0, 1.0);
      // Round-off must not hand a weight of 1e-17 to a point outside the ray's cell.
      if (frac[a] < 1e-12) frac[a] = 0;
      if (frac[a] > 1 - 1e-12) frac[a] = 1;
    }
    for (int c = 0; c < 8; ++c) {
      const int d[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
      double w = 1;
      for (int a = 0; a < 3; ++a) w *= d[a] ? frac[a] : 1 - frac[a];
      row.index[static_cast<std::size_t>(c)] = lv.at(cell[0] + d[0], cell[1] + d[1], cell[2] + d[2]);
      row.weight[static_cast<std::size_t>(c)] = w;
    }
    rows.push_back(row);
  });
  return rows;
}

namespace {

double interpolated(const RayStencil& row, const double* u) {
  double v = 0;
  for (std::size_t c = 0; c < 8; ++c) v += row.weight[c] * u[row.index[c]];
  return v;
}

}  // namespace

void robin_residual(const std::vector<RayStencil>& rows, double u_inf, const double* u, const double* rhs,
                    const std::uint8_t* fixed, double* res) {
  for (const RayStencil& row : rows) {
    const std::ptrdiff_t p = row.point;
    if (fixed && fixed[p]) {
      res[p] = 0;
      continue;
    }
    const double b = (u[p] - u_inf) - row.scale * (interpolated(row, u) - u_inf);
    res[p] = (rhs ? rhs[p] : 0.0) - b;
  }
}

void robin_relax(const std::vector<RayStencil>& rows, double u_inf, double* u, const double* rhs,
                 const std::uint8_t* fixed) {
  for (const RayStencil& row : rows) {
    const std::ptrdiff_t p = row.point;
    if (fixed && fixed[p]) continue;
    u[p] = u_inf + row.scale * (interpolated(row, u) - u_inf) + (rhs ? rhs[p] : 0.0);
  }
}

void zero_faces(const Level& lv, double* res) {
  for_face_points(lv, [&](int i, int j, int k) { res[lv.at(i, j, k)] = 0.0; });
}

}  // namespace bhnsid::multigrid
