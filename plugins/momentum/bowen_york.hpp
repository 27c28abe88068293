#pragma once
// The Bowen-York part of the conformal extrinsic curvature (physics-notes §2.6; hatted, with Phat):
//   Ahat_BY^ij = 3/(2 r^2) [P^i n^j + P^j n^i - (delta^ij - n^i n^j)(P.n)],  n = (x - x_BH)/r.
// Traceless and divergence-free for r > 0; r = 0 is never asked (the puncture is off the grid).
#include <array>
#include <cmath>

namespace bhnsid::momentum {

inline std::array<double, 6> bowen_york(const std::array<double, 3>& mom, const std::array<double, 3>& x_bh,
                                        const std::array<double, 3>& x) {
  const double d[3] = {x[0] - x_bh[0], x[1] - x_bh[1], x[2] - x_bh[2]};
  const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], r = std::sqrt(r2);
  const double n[3] = {d[0] / r, d[1] / r, d[2] / r};
  const double pn = mom[0] * n[0] + mom[1] * n[1] + mom[2] * n[2];
  const double c = 1.5 / r2;
  // Written out (no loops): a loop nest here keeps every grid loop that calls this scalar.
  auto component = [&](int a, int b) {
    return c * (mom[a] * n[b] + mom[b] * n[a] - ((a == b ? 1.0 : 0.0) - n[a] * n[b]) * pn);
  };
  const std::array<double, 6> out = {component(0, 0), component(0, 1), component(0, 2),
                                     component(1, 1), component(1, 2), component(2, 2)};
  return out;
}

/// sum_ij (A^ij)^2 of a symmetric tensor stored as xx, xy, xz, yy, yz, zz.
inline double squared_norm(const std::array<double, 6>& t) {
  return t[0] * t[0] + t[3] * t[3] + t[5] * t[5] + 2.0 * (t[1] * t[1] + t[2] * t[2] + t[4] * t[4]);
}

}  // namespace bhnsid::momentum
