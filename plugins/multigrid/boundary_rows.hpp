#pragma once
// Outer-boundary rows of the system: the Robin condition (u - u_inf) + (x - x0) . grad u = 0 at
// every stored point on a face of the cube (physics-notes §5.2). It says that r (u - u_inf) is
// constant along each ray from the centre x0, and that is how it is discretised here: for a face
// point x_b and the point x_in = x0 + s (x_b - x0), s = 1 - h / |x_b - x0|_inf, one cell further
// in along the same ray,
//     (u_b - u_inf) = s (u(x_in) - u_inf),
// exact for every u_inf + f(angles)/|x - x0|, like the differential form. x_in lies on the grid
// plane one cell inside the face, so u(x_in) is interpolated in the (at most two) tangential
// directions, by 3-point Lagrange interpolation on the points around x_b's own index: O(h^3).
// The order matters: the rows fix the level of the whole solution through the factor
// 1/(1 - s) = r/h, so an interpolation error e becomes a global error e r/h. Trilinear
// interpolation (e ~ h^2) made the solution only first-order accurate near the faces (the ADM
// mass from the 1/r falloff converged like h/r_c); quadratic gives O(h^2) everywhere. The
// stencil stays within one point of x_b tangentially (two, inward, at edges), so the rows reach
// no further than the coarse solver's colouring allows. The literal form with one-sided normal
// derivatives and centred tangential ones (§5.2) was tried first: its rows are not diagonally
// dominant and red-black Gauss-Seidel on them diverged (residual x1.4 per sweep). Here each row
// fixes u_b from interior values with weights summing to s < 1 (the few negative weights of the
// quadratic are at most 1/8), so relaxing the rows converges. The rows are equations of the FAS
// system like the interior ones: relaxed in every sweep, their residuals injected to the coarse level.
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
  std::array<std::ptrdiff_t, 9> index;  ///< up to 3 x 3 tangential points (weight 0 where unused)
  std::array<double, 9> weight;
  double scale;
};

/// The rows of every face point of a level for a condition about `centre`; throws
/// core::RunFailure when the centre is closer than 1.5 cells to a face.
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
