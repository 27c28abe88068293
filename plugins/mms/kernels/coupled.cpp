#include "kernels/coupled.hpp"

#include <stdexcept>

#include "bhnsid/interfaces/scalar_sweep.hpp"

namespace bhnsid::mms::kernels {

using stencil::LocalTerm;
using stencil::scalar_relax_any;
using stencil::scalar_residual_any;

namespace {

template <int Power>
struct OtherTerm {
  static constexpr bool linear = true;
  const double* s;
  const double* other;
  double coef;
  LocalTerm at(std::ptrdiff_t idx, double) const {
    const double q = other[idx];
    if constexpr (Power == 1)
      return {coef * q + s[idx], 0.0};
    else
      return {coef * q * q * q + s[idx], 0.0};
  }
};

// Calls fn(OtherTerm<1>{...}) or fn(OtherTerm<3>{...}).
template <class Fn>
void with_power(int power, const double* source, const double* other, double coef, Fn&& fn) {
  if (power == 1)
    fn(OtherTerm<1>{source, other, coef});
  else if (power == 3)
    fn(OtherTerm<3>{source, other, coef});
  else
    throw std::logic_error("mms: the coupled kernels take power 1 or 3");
}

}  // namespace

void coupled_residual(const Level& lv, const double* own, const double* other, double coef, int power,
                      const double* source, const double* rhs, const std::uint8_t* fixed, double* out) {
  with_power(power, source, other, coef,
             [&](const auto& local) { scalar_residual_any(lv, own, rhs, fixed, out, local); });
}

void coupled_relax(const Level& lv, double* own, const double* other, double coef, int power, const double* source,
                   const double* rhs, const std::uint8_t* fixed, double omega, const Mirror& mirror) {
  with_power(power, source, other, coef,
             [&](const auto& local) { scalar_relax_any(lv, own, rhs, fixed, omega, mirror, local); });
}

}  // namespace bhnsid::mms::kernels
