#pragma once
// Outer-boundary rows of the system: the Robin condition (u - u_inf) + (x - x0) . grad u = 0 at
// every stored point on a face of the cube (physics-notes §5.2). It says that r (u - u_inf) is
// constant along each ray from the centre x0, and that is how it is discretised here: for a face
// point x_b and the point x_in = x0 + s (x_b - x0), s = 1 - h / |x_b - x0|_inf, one cell further
// in along the same ray,
//     (u_b - u_inf) = s (u(x_in) - u_inf),   u(x_in) by trilinear interpolation (second order).
// Exact for every u_inf + f(angles)/|x - x0|, like the differential form. The literal form with
// one-sided normal derivatives and centred tangential ones (§5.2) was tried first: its rows are
// not diagonally dominant and red-black Gauss-Seidel on them diverged (residual x1.4 per sweep).
// Here each row fixes u_b from interior values with positive weights summing to s < 1, so the
// relaxation is a contraction. The rows are equations of the FAS system like the interior ones:
// relaxed in every sweep, their residuals injected to the coarse level.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::multigrid {

struct RobinRow {
  double u_inf = 0;
  std::array<double, 3> centre{};
};

/// One face point's row: u[point] - u_inf = scale (sum_k weight[k] u[index[k]] - u_inf).
struct RayStencil {
  std::ptrdiff_t point;
  std::array<std::ptrdiff_t, 8> index;
  std::array<double, 8> weight;
  double scale;
};

/// The rows of every face point of a level for a condition about `centre`; throws
/// core::RunFailure when the centre is closer than 2 cells to a face.
std::vector<RayStencil> robin_stencils(const Level& lv, const std::array<double, 3>& centre);

/// res = rhs - B(u) at the face points (rhs may be nullptr: zero); 0 at held points.
void robin_residual(const std::vector<RayStencil>& rows, double u_inf, const double* u, const double* rhs,
                    const std::uint8_t* fixed, double* res);

/// Each face point solved for its own row, in turn (Gauss-Seidel).
void robin_relax(const std::vector<RayStencil>& rows, double u_inf, double* u, const double* rhs,
                 const std::uint8_t* fixed);

/// res = 0 at every face point (Dirichlet rows are satisfied by construction).
void zero_faces(const Level& lv, double* res);

/// Calls fn(i, j, k) for every stored point on an outer face of the cube.
template <class Fn>
void for_face_points(const Level& lv, Fn&& fn) {
  for (int k = 0; k < lv.nz; ++k) {
    const bool face_plane = k == lv.nz - 1 || (k == 0 && !lv.z_symmetry);
    for (int j = 0; j < lv.ny; ++j) {
      if (face_plane || j == 0 || j == lv.ny - 1) {
        for (int i = 0; i < lv.nx; ++i) fn(i, j, k);
      } else {
        fn(0, j, k);
        fn(lv.nx - 1, j, k);
      }
    }
  }
}

}  // namespace bhnsid::multigrid
