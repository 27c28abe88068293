#pragma once
// One equation of the coupled pair: L(own) = lap own + coef * other^power + s, power 1 or 3. The
// other equation's unknown is only read, so each equation's Gauss-Seidel moves its own unknown,
// and the row is linear in it: the Newton step is the point solve.
#include <cstdint>

#include "bhnsid/interfaces/grid.hpp"
#include "kernels/common.hpp"

namespace bhnsid::mms::kernels {

/// out = rhs - (lap own + coef other^power + source); power is 1 or 3.
void coupled_residual(const Level& lv, const double* own, const double* other, double coef, int power,
                      const double* source, const double* rhs, const std::uint8_t* fixed, double* out);

/// One red-black Gauss-Seidel sweep on `own`, `other` held; arguments as for laplace_relax.
void coupled_relax(const Level& lv, double* own, const double* other, double coef, int power, const double* source,
                   const double* rhs, const std::uint8_t* fixed, double omega, const Mirror& mirror);

}  // namespace bhnsid::mms::kernels
