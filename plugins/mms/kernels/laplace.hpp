#pragma once
// The linear scalar operator L(u) = lap u + s (7-point Laplacian), used by the poisson and ball
// problems and timed by the benchmark.
#include <cstdint>

#include "bhnsid/interfaces/grid.hpp"
#include "kernels/common.hpp"

namespace bhnsid::mms::kernels {

/// out = rhs - (lap u + source) at every interior point (rhs nullptr: zero); 0 where fixed != 0
/// (fixed nullptr: no held points).
void laplace_residual(const Level& lv, const double* u, const double* source, const double* rhs,
                      const std::uint8_t* fixed, double* out);

/// One red-black Gauss-Seidel sweep (colour 0, then 1) toward lap u + source = rhs: each interior,
/// non-held point moves by omega times its point solve. mirror() refreshes the ghost plane between
/// the colours under equatorial symmetry.
void laplace_relax(const Level& lv, double* u, const double* source, const double* rhs, const std::uint8_t* fixed,
                   double omega, const Mirror& mirror);

}  // namespace bhnsid::mms::kernels
