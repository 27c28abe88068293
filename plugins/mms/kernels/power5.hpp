#pragma once
// The nonlinear scalar operator L(u) = lap u + c u^5 + s, shaped like the Hamiltonian constraint's
// matter term (2 pi rho psi^5 has c > 0; c < 0 gives a monotone operator).
#include <cstdint>

#include "bhnsid/interfaces/grid.hpp"
#include "kernels/common.hpp"

namespace bhnsid::mms::kernels {

/// out = rhs - (lap u + c u^5 + source); arguments as for laplace_residual.
void power5_residual(const Level& lv, const double* u, double c, const double* source, const double* rhs,
                     const std::uint8_t* fixed, double* out);

/// One nonlinear red-black Gauss-Seidel sweep: u -= omega (L - rhs) / (-6/h^2 + 5 c u^4) at each
/// point; arguments as for laplace_relax.
void power5_relax(const Level& lv, double* u, double c, const double* source, const double* rhs,
                  const std::uint8_t* fixed, double omega, const Mirror& mirror);

}  // namespace bhnsid::mms::kernels
