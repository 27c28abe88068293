#pragma once
// Outer-boundary rows of the system: the Robin condition (u - u_inf) + (x - x0) . grad u = 0 at
// every stored point on a face of the cube (physics-notes §5.2). It says that v = r (u - u_inf) is
// constant along each ray from the centre x0, dv/dr = 0, and that is how it is discretised here:
// for a face point x_b the points x_m = x0 + s_m (x_b - x0), s_m = 1 - m h / |x_b - x0|_inf, lie on
// the same ray on the grid planes m = 1, 2 cells inside the face, equally spaced in r, and the
// one-sided second-order difference 3 v_b - 4 v_1 + v_2 = 0 gives the row
//     (u_b - u_inf) = (4 s_1 (u(x_1) - u_inf) - s_2 (u(x_2) - u_inf)) / 3,
// exact for every u_inf + f(angles)/|x - x0| like the differential form, and a second-order
// approximation of dv/dr = 0 at the face otherwise. u(x_m) is interpolated in the (at most two)
// tangential directions by 3-point Lagrange interpolation: O(h^3).
// The order matters: the rows fix the level of the whole solution through the factor
// 1/(1 - s_1) = r/h, so a row error e becomes a global error e r/h. Trilinear interpolation
// (e ~ h^2) made the solution only first-order accurate near the faces (the ADM mass from the 1/r
// falloff converged like h/r_c). So did the two-point row (u_b - u_inf) = s_1 (u(x_1) - u_inf) used
// before: it is dv/dr = 0 imposed half a cell inside the face, an O(h) error for every field that
// is not a pure monopole (the ball's dipole, a boosted puncture's chi and eta converged at first
// order with r_c fixed). The interpolation windows are 3 consecutive indices that contain x_b's own
// index and both targets (shifted toward the centre where the targets are more than half a cell
// off), so no row reaches further than 2 indices from its own per axis: the coarse solver's
// colouring (mod 5) relies on that. The literal form with one-sided normal derivatives and centred tangential
// ones (§5.2) was tried first: its rows are not diagonally dominant and red-black Gauss-Seidel on
// them diverged (residual x1.4 per sweep). Here each row fixes u_b from other values with weights
// summing to (4 s_1 - s_2)/3 < 1, so relaxing the rows converges. The rows are equations of the FAS
// system like the interior ones: relaxed in every sweep, their residuals injected to the coarse level.
// A level with a face closer than 2.5 cells to the centre (the coarsest) keeps the two-point row.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::multigrid {

/// A std::vector whose resize() leaves new elements uninitialised: robin_stencils sizes its arrays
/// first and the threads then write their rows, so that each page is first touched by the thread
/// that fills it, not by a serial zero fill (14 MB of rows per row set on the finest level at
/// n = 128).
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <class T>
using RowArray = std::vector<T, UninitialisedAllocator<T>>;

/// The rows of every face point of a level, stored compactly (weights that vanish are dropped):
/// row r says u[point[r]] - u_inf = sum over e in [begin[r], begin[r+1]) of weight[e] (u[index[e]] - u_inf).
struct RobinRows {
  RowArray<std::ptrdiff_t> point;
  RowArray<std::size_t> begin{0};
  RowArray<std::ptrdiff_t> index;
  RowArray<double> weight;
  RowArray<double> scale;            ///< per row: the sum of its weights, < 1
  mutable std::vector<double> next;  ///< scratch of robin_relax
  std::size_t size() const { return point.size(); }
};

/// The rows of every face point of a level for a condition about `centre`; throws
/// core::RunFailure when the centre is closer than 1.5 cells to a face point, except on a coarse
/// level (`coarse`), where such a point's row is about the centre moved out along the face's normal
/// to 1.5 cells (a coarse level carries only FAS corrections). `two_point` forces the
/// first-order row of every level (kept to measure what the second-order one gains).
RobinRows robin_stencils(const Level& lv, const std::array<double, 3>& centre, bool two_point, bool coarse = false);

/// One array whose face points obey the rows.
struct RobinTarget {
  double* u;
  double u_inf;
  const double* rhs;            ///< nullptr: zero
  const std::uint8_t* fixed;    ///< nullptr: nothing held
};

/// One array's row residuals: res = rhs - B(u) at the face points (rhs nullptr: zero), 0 at held points.
struct RobinResidual {
  const double* u;
  double u_inf;
  const double* rhs;
  const std::uint8_t* fixed;
  double* res;
};

/// The residuals of every array in one pass, so that the rows' indices and weights stream through
/// memory once for all of them.
void robin_residual(const RobinRows& rows, const std::vector<RobinResidual>& fields);
inline void robin_residual(const RobinRows& rows, double u_inf, const double* u, const double* rhs,
                           const std::uint8_t* fixed, double* res) {
  robin_residual(rows, {RobinResidual{u, u_inf, rhs, fixed, res}});
}

/// The same residuals row by row into out[r * fields.size() + t] (field t's res unused): the solver
/// forms those of all equations that share the rows in one pass and hands them out one equation at
/// a time.
void robin_residual_rows(const RobinRows& rows, const std::vector<RobinResidual>& fields, double* out);

/// Every face point of every target solved for its own row from the values before the call
/// (Jacobi: the rows are independent of each other but for the few that lean on another face
/// point, a contraction with weights < 1/8, and Jacobi lets the threads share them). All targets
/// in one pass, as robin_residual.
void robin_relax(const RobinRows& rows, const std::vector<RobinTarget>& targets);
inline void robin_relax(const RobinRows& rows, double u_inf, double* u, const double* rhs, const std::uint8_t* fixed) {
  robin_relax(rows, {RobinTarget{u, u_inf, rhs, fixed}});
}

/// res = 0 at every face point (Dirichlet rows are satisfied by construction).
void zero_faces(const Level& lv, double* res);

/// Calls fn(j, k, whole) for every row (j, k) that holds stored points on an outer face of the cube,
/// in order: whole (all of i = 0 .. nx-1 on the faces) on a face plane and on the y faces, else its
/// two end points i = 0 and nx-1 on the x faces.
template <class Fn>
void for_face_rows(const Level& lv, Fn&& fn) {
  for (int k = 0; k < lv.nz; ++k) {
    const bool face_plane = k == lv.nz - 1 || (k == 0 && !lv.z_symmetry);
    for (int j = 0; j < lv.ny; ++j) fn(j, k, face_plane || j == 0 || j == lv.ny - 1);
  }
}

/// Calls fn(i) for the face points of row (j, k) as for_face_rows gives it, in order.
template <class Fn>
void for_points_of_face_row(const Level& lv, bool whole, Fn&& fn) {
  if (whole) {
    for (int i = 0; i < lv.nx; ++i) fn(i);
  } else {
    fn(0);
    fn(lv.nx - 1);
  }
}

/// Calls fn(i, j, k) for every stored point on an outer face of the cube.
template <class Fn>
void for_face_points(const Level& lv, Fn&& fn) {
  for_face_rows(lv, [&](int j, int k, bool whole) { for_points_of_face_row(lv, whole, [&](int i) { fn(i, j, k); }); });
}

}  // namespace bhnsid::multigrid
