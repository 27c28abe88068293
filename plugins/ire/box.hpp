#pragma once
// The finest level's stored points as the evaluator sees them: plain arrays of its own (no grid
// ghosts), with reads below the symmetry plane z = 0 mirrored by the component's parity. Every
// component's parity under z -> -z is (-1)^(number of z indices): scalars, tensors and the
// Christoffel symbols alike (no time reversal is involved in the equatorial reflection).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::ire {

struct Box {
  int nx = 0, ny = 0, nz = 0;
  bool mirror = false;  ///< equatorial symmetry: k = 0 is z = 0, k < 0 reads k > 0
  double dx = 0;
  double x0 = 0, y0 = 0, z0 = 0;

  explicit Box(const Level& lv)
      : nx(lv.nx), ny(lv.ny), nz(lv.nz), mirror(lv.z_symmetry), dx(lv.dx), x0(lv.origin[0]), y0(lv.origin[1]),
        z0(lv.origin[2]) {}
  std::size_t size() const { return static_cast<std::size_t>(nx) * ny * nz; }
  std::size_t at(int i, int j, int k) const {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * k);
  }
  /// Whether a stencil reaching `margin` points in every direction fits around (i, j, k).
  bool inside(int i, int j, int k, int margin) const {
    const bool z_ok = mirror ? k >= 0 && k <= nz - 1 - margin : k >= margin && k <= nz - 1 - margin;
    return i >= margin && i <= nx - 1 - margin && j >= margin && j <= ny - 1 - margin && z_ok;
  }
};

/// One component on the box; zsign is its parity under z -> -z. A field with `slot` holds values
/// only at some points (the derived quantities where the residuals need them): v[slot[at(i, j, k)]].
struct Field {
  // Not zero-filled on allocation: every value is written by the fill that creates it, in parallel,
  // so the pages are touched once (fresh memory is slow to touch the first time on our VMs).
  std::unique_ptr<double[]> v;
  double zsign = 1;
  const std::vector<std::int32_t>* slot = nullptr;
  double& at(const Box& b, int i, int j, int k) {
    const std::size_t p = b.at(i, j, k);
    return v[slot ? static_cast<std::size_t>((*slot)[p]) : p];
  }
};

inline double get(const Box& b, const Field& f, int i, int j, int k) {
  std::size_t p = b.at(i, j, k < 0 ? -k : k);
  if (f.slot) p = static_cast<std::size_t>((*f.slot)[p]);
  return k >= 0 ? f.v[p] : f.zsign * f.v[p];
}

/// Centred first difference along axis a (0, 1, 2) at (i, j, k).
inline double d0(const Box& b, const Field& f, int a, int i, int j, int k) {
  const int di = a == 0, dj = a == 1, dk = a == 2;
  return (get(b, f, i + di, j + dj, k + dk) - get(b, f, i - di, j - dj, k - dk)) / (2.0 * b.dx);
}

/// Parity sign of a component with the given number of z indices.
inline double zparity(int z_indices) { return z_indices % 2 ? -1.0 : 1.0; }

/// Symmetric pair (a, b) -> 0..5 in the order xx, xy, xz, yy, yz, zz.
inline int pair(int a, int b) {
  static constexpr int table[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  return table[a][b];
}

}  // namespace bhnsid::ire
