#pragma once
// The vector operator of the momentum constraint and the shift equation,
//   L(V)^i = lap V^i + (1/3) d^i d_j V^j - kappa n^i n_j V^j + s^i,   n = x / r_c,
// second-order centred differences, mixed derivatives by the 4-point stencil
// (f(+a,+b) - f(+a,-b) - f(-a,+b) + f(-a,-b)) / 4h^2. The kappa term (zero in the momentum
// operator) couples the three components at a point, so that the point update is a genuine 3x3 solve.
#include <array>
#include <cstdint>

#include "bhnsid/interfaces/grid.hpp"
#include "kernels/common.hpp"

namespace bhnsid::mms::kernels {

using ConstComponents = std::array<const double*, 3>;
using Components = std::array<double*, 3>;  // as stencil::Components (vector_sweep.hpp)

/// out^i = rhs^i - L(V)^i at every interior point (rhs nullptr: zero, else one array per
/// component), 0 where fixed != 0.
void vector_residual(const Level& lv, ConstComponents v, ConstComponents source, double kappa,
                     const double* const* rhs, const std::uint8_t* fixed, Components out);

/// One red-black Gauss-Seidel sweep (colour 0, then 1) toward L(V) = rhs: at each interior,
/// non-held point the three components take omega times the Newton step -J^{-1} (L - rhs), J the
/// 3x3 derivative of the point's rows by its own unknowns. The centred mixed stencil does not touch
/// the centre, so J = -(20/3)/h^2 I - kappa n n^T; with kappa = 0 it is diagonal and the solve a
/// division. mirror() refreshes the ghost plane of all three components between the colours.
void vector_relax(const Level& lv, Components v, ConstComponents source, double kappa, const double* const* rhs,
                  const std::uint8_t* fixed, double omega, const Mirror& mirror);

}  // namespace bhnsid::mms::kernels
