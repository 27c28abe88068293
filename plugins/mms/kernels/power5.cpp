#include "kernels/power5.hpp"

#include "bhnsid/interfaces/scalar_sweep.hpp"

namespace bhnsid::mms::kernels {

using stencil::LocalTerm;
using stencil::scalar_relax_any;
using stencil::scalar_residual_any;

namespace {

struct Power5 {
  static constexpr bool linear = false;
  const double* s;
  double c;
  LocalTerm at(std::ptrdiff_t idx, double u) const {
    const double u4 = (u * u) * (u * u);
    return {c * u4 * u + s[idx], 5.0 * c * u4};
  }
};

}  // namespace

void power5_residual(const Level& lv, const double* u, double c, const double* source, const double* rhs,
                     const std::uint8_t* fixed, double* out) {
  scalar_residual_any(lv, u, rhs, fixed, out, Power5{source, c});
}

void power5_relax(const Level& lv, double* u, double c, const double* source, const double* rhs,
                  const std::uint8_t* fixed, double omega, const Mirror& mirror) {
  scalar_relax_any(lv, u, rhs, fixed, omega, mirror, Power5{source, c});
}

}  // namespace bhnsid::mms::kernels
