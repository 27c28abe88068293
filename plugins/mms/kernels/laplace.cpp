#include "kernels/laplace.hpp"

#include "bhnsid/interfaces/scalar_sweep.hpp"

namespace bhnsid::mms::kernels {

using stencil::LocalTerm;
using stencil::scalar_relax_any;
using stencil::scalar_residual_any;

namespace {

struct SourceOnly {
  static constexpr bool linear = true;
  const double* s;
  LocalTerm at(std::ptrdiff_t idx, double) const { return {s[idx], 0.0}; }
};

}  // namespace

void laplace_residual(const Level& lv, const double* u, const double* source, const double* rhs,
                      const std::uint8_t* fixed, double* out) {
  scalar_residual_any(lv, u, rhs, fixed, out, SourceOnly{source});
}

void laplace_relax(const Level& lv, double* u, const double* source, const double* rhs, const std::uint8_t* fixed,
                   double omega, const Mirror& mirror) {
  scalar_relax_any(lv, u, rhs, fixed, omega, mirror, SourceOnly{source});
}

}  // namespace bhnsid::mms::kernels
