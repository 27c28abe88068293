#pragma once
// The example plugin's problem: -u'' = pi^2 sin(pi x) on [0, 1], u(0) = u(1) = 0, whose exact
// solution is u = sin(pi x). Second-order centred differences, relaxed by red-black SOR.
#include <string>
#include <vector>

namespace bhnsid::demo_poisson1d {

class Poisson1d {
 public:
  Poisson1d(int points, double omega);

  /// `count` red-black SOR sweeps.
  void relax(int count);
  /// max |f + u''| over the interior, relative to max |f|.
  double relative_residual() const;
  /// max |u - sin(pi x)| over the grid.
  double error_max() const;
  /// "x u exact" lines with a header.
  std::string table() const;

  int points() const { return static_cast<int>(u_.size()); }

 private:
  double x(int i) const { return i * h_; }
  std::vector<double> u_, f_;
  double h_, omega_;
};

}  // namespace bhnsid::demo_poisson1d
