#pragma once
// The fields the apparent-horizon condition reads, sampled in a box about the puncture: chi and
// Zhat^ij = Ahat^ij - Ahat_BY^ij copied from the finest level (symmetry images filled by parity),
// interpolated with 4-point Lagrange polynomials per axis, value and gradient. The puncture's own
// parts, Mhat/(2 rhat) of phi and the Bowen-York Ahat_BY, are added exactly: at the horizon
// (rhat ~ Mhat/2, a few spacings on the paper's grids) they vary on the scale of one cell.
#include <array>
#include <vector>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::horizon {

struct Hole {
  double mass = 0;                  ///< Mhat_BH
  std::array<double, 3> position{}; ///< xhat_BH
  std::array<double, 3> momentum{}; ///< Phat_BH
};

/// Ahat_BY^ij = 3/(2 r^2) [P^i n^j + P^j n^i - (delta^ij - n^i n^j) P.n], stored xx, xy, xz, yy, yz, zz.
std::array<double, 6> bowen_york(const Hole& hole, const std::array<double, 3>& x);

/// phi, grad ln phi and Ahat^ij at one point (hatted).
struct FieldPoint {
  double phi = 1;
  std::array<double, 3> dlnphi{};
  std::array<double, 6> ahat{};
};

class LocalFields {
 public:
  /// Copies the box [xhat_BH - half, xhat_BH + half]^3 (plus the interpolation's reach) of chi and, if
  /// `ahat` >= 0, of Ahat - Ahat_BY from the finest level. core::RunFailure when the box leaves the grid.
  LocalFields(const Grid& grid, int chi, int ahat, const Hole& hole, double half);

  /// Inside the box where the stencils fit (the surface must stay there).
  bool covers(const std::array<double, 3>& x) const;
  FieldPoint at(const std::array<double, 3>& x) const;
  const Hole& hole() const { return hole_; }
  double spacing() const { return dx_; }

 private:
  /// Value and gradient of the box array `f` at x (4-point Lagrange per axis).
  void sample(const std::vector<double>& f, const std::array<double, 3>& x, double& value, std::array<double, 3>& grad) const;
  std::size_t index(int i, int j, int k) const { return static_cast<std::size_t>(i + n_[0] * (j + n_[1] * k)); }

  Hole hole_;
  double dx_ = 0;
  std::array<double, 3> origin_{};  ///< coordinates of box point (0, 0, 0)
  std::array<int, 3> n_{};
  std::vector<double> chi_;
  std::array<std::vector<double>, 6> zhat_;
  bool has_zhat_ = false;
};

}  // namespace bhnsid::horizon
