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
    // The ray needs a point one cell in (s > 0) with room around it; 1.5 cells keeps s >= 1/3 and lets
    // a centre just off the origin pass on a coarsest level of 4 intervals (face 2 cells away).
    if (reach < 1.5 * lv.dx)
      throw core::RunFailure(fmt::format(
          "multigrid: the Robin centre ({}, {}, {}) is within 1.5 cells of the face point ({}, {}, {}) on level {}",
          centre[0], centre[1], centre[2], xb[0], xb[1], xb[2], lv.index));
    RayStencil row;
    row.point = lv.at(i, j, k);
    row.scale = 1.0 - lv.dx / reach;
    // Per axis: the points it uses and their weights. The axis (or axes) with |X_a| = reach is
    // exact: x_in lies on the grid plane one cell in. Other axes interpolate with 3 points around
    // x_b's own index (shifted inward at the cube's edges), x_in lying within one cell of x_b.
    int first[3], count[3];
    double w[3][3];
    const int own[3] = {i, j, k};
    for (int a = 0; a < 3; ++a) {
      const double t = (centre[a] + row.scale * X[a] - lv.origin[a]) / lv.dx;
      const double nearest = std::round(t);
      if (std::fabs(t - nearest) < 1e-9) {
        first[a] = std::clamp(static_cast<int>(nearest), 0, last[a]);
        count[a] = 1;
        w[a][0] = 1;
        continue;
      }
      first[a] = std::clamp(own[a] - 1, 0, last[a] - 2);
      count[a] = 3;
      const double u = t - first[a];  // nodes at 0, 1, 2
      w[a][0] = 0.5 * (u - 1) * (u - 2);
      w[a][1] = -u * (u - 2);
      w[a][2] = 0.5 * u * (u - 1);
    }
    row.index.fill(row.point);
    row.weight.fill(0.0);
    std::size_t c = 0;
    for (int p = 0; p < count[0]; ++p)
      for (int q = 0; q < count[1]; ++q)
        for (int r = 0; r < count[2]; ++r) {
          if (c == row.index.size())
            throw core::RunFailure(fmt::format("multigrid: the Robin row of face point ({}, {}, {}) on level {} needs "
                                               "interpolation along three axes",
                                               i, j, k, lv.index));
          row.index[c] = lv.at(first[0] + p, first[1] + q, first[2] + r);
          row.weight[c] = w[0][p] * w[1][q] * w[2][r];
          ++c;
        }
    rows.push_back(row);
  });
  return rows;
}

namespace {

double interpolated(const RayStencil& row, const double* u) {
  double v = 0;
  for (std::size_t c = 0; c < row.index.size(); ++c) v += row.weight[c] * u[row.index[c]];
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
