#include "poisson1d.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace bhnsid::demo_poisson1d {

Poisson1d::Poisson1d(int points, double omega)
    : u_(static_cast<std::size_t>(points), 0.0), f_(static_cast<std::size_t>(points)), h_(1.0 / (points - 1)),
      omega_(omega) {
  const double pi = std::numbers::pi;
  for (int i = 0; i < points; ++i) f_[i] = pi * pi * std::sin(pi * x(i));
}

void Poisson1d::relax(int count) {
  const int n = points();
  double* u = u_.data();
  const double* f = f_.data();
  const double h2 = h_ * h_;
  for (int sweep = 0; sweep < count; ++sweep)
    for (int colour = 1; colour <= 2; ++colour)
      for (int i = colour; i < n - 1; i += 2) {
        const double gauss_seidel = 0.5 * (u[i - 1] + u[i + 1] + h2 * f[i]);
        u[i] += omega_ * (gauss_seidel - u[i]);
      }
}

double Poisson1d::relative_residual() const {
  const int n = points();
  double r = 0, fmax = 0;
  for (int i = 1; i < n - 1; ++i) {
    r = std::max(r, std::abs(f_[i] + (u_[i - 1] - 2 * u_[i] + u_[i + 1]) / (h_ * h_)));
    fmax = std::max(fmax, std::abs(f_[i]));
  }
  return fmax > 0 ? r / fmax : r;
}

double Poisson1d::error_max() const {
  double e = 0;
  for (int i = 0; i < points(); ++i) e = std::max(e, std::abs(u_[i] - std::sin(std::numbers::pi * x(i))));
  return e;
}

std::string Poisson1d::table() const {
  std::string out = "# x\tu\texact\n";
  for (int i = 0; i < points(); ++i)
    out += fmt::format("{:.17g}\t{:.17g}\t{:.17g}\n", x(i), u_[i], std::sin(std::numbers::pi * x(i)));
  return out;
}

}  // namespace bhnsid::demo_poisson1d
