#include "fill.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bhnsid_reader.h"

namespace bhnsid::reader {

namespace {

bool inside(const HeldRegion& r, double tol, double dx, double dy, double dz) {
  if (r.cube) return std::max({std::fabs(dx), std::fabs(dy), std::fabs(dz)}) <= r.half_size + tol;
  return std::sqrt(dx * dx + dy * dy + dz * dz) <= r.half_size + tol;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

}  // namespace

bool in_held_region(const HeldRegion& r, const Grid& g, double x, double y, double z) {
  const double tol = 1e-9 * g.dx;
  const double dx = x - r.centre[0], dy = y - r.centre[1];
  return inside(r, tol, dx, dy, z - r.centre[2]) || (g.equatorial && inside(r, tol, dx, dy, -z - r.centre[2]));
}

std::size_t harmonic_fill(const Grid& g, const HeldRegion& r, int parity, std::vector<double>& values,
                          const std::string& path) {
  // The index box that can hold the region (and its mirror), one point wider on each side. Clamped
  // to the grid while still a double: a half-size or centre of 1e300 must mean "the whole grid"
  // (and be refused below as 1e6 is), not overflow the conversion to int.
  const double h = r.half_size;
  const double bound = 1.0 + std::max({g.nx, g.ny, g.nz});
  const auto index = [&](double t) { return static_cast<int>(std::clamp(t, -bound, bound)); };
  const auto lo = [&](double c, double o) { return index(std::floor((c - h - o) / g.dx) - 1); };
  const auto hi = [&](double c, double o) { return index(std::ceil((c + h - o) / g.dx) + 1); };
  const int i0 = std::max(0, lo(r.centre[0], g.origin[0])), i1 = std::min(g.nx - 1, hi(r.centre[0], g.origin[0]));
  const int j0 = std::max(0, lo(r.centre[1], g.origin[1])), j1 = std::min(g.ny - 1, hi(r.centre[1], g.origin[1]));
  const double cz_lo = g.equatorial ? std::min(r.centre[2], -r.centre[2]) : r.centre[2];
  const double cz_hi = g.equatorial ? std::max(r.centre[2], -r.centre[2]) : r.centre[2];
  const int k0 = std::max(g.kmin(), lo(cz_lo, g.origin[2])), k1 = std::min(g.nz - 1, hi(cz_hi, g.origin[2]));
  if (i0 > i1 || j0 > j1 || k0 > k1) return 0;
  const int bx = i1 - i0 + 1, by = j1 - j0 + 1, bz = k1 - k0 + 1;

  // Unknowns: the full-grid points (mirror included) inside the region.
  std::vector<int> id(static_cast<std::size_t>(bx) * by * bz, -1);
  const auto box = [&](int i, int j, int k) {
    return (static_cast<std::size_t>(k - k0) * by + static_cast<std::size_t>(j - j0)) * bx + static_cast<std::size_t>(i - i0);
  };
  std::vector<std::array<int, 3>> points;
  for (int k = k0; k <= k1; ++k)
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        if (in_held_region(r, g, g.origin[0] + g.dx * i, g.origin[1] + g.dx * j, g.origin[2] + g.dx * k)) {
          id[box(i, j, k)] = static_cast<int>(points.size());
          points.push_back({i, j, k});
        }
  const std::size_t n = points.size();
  if (n == 0) return 0;
  const auto unknown = [&](int i, int j, int k) {
    if (i < i0 || i > i1 || j < j0 || j > j1 || k < k0 || k > k1) return -1;
    return id[box(i, j, k)];
  };
  const auto stored = [&](int i, int j, int k) {
    return k >= 0 ? values[g.at(i, j, k)] : parity * values[g.at(i, j, -k)];
  };

  // A u = b with A = (in-grid neighbours) I - adjacency: symmetric positive definite once any
  // neighbour is known data. A neighbour beyond the grid's edge drops out (zero normal derivative).
  std::vector<std::array<int, 6>> nbr(n);
  std::vector<double> diag(n, 0), b(n, 0);
  std::size_t known = 0;
  static constexpr int offsets[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  for (std::size_t u = 0; u < n; ++u) {
    for (int d = 0; d < 6; ++d) {
      const int i = points[u][0] + offsets[d][0], j = points[u][1] + offsets[d][1], k = points[u][2] + offsets[d][2];
      nbr[u][static_cast<std::size_t>(d)] = -1;
      if (i < 0 || i >= g.nx || j < 0 || j >= g.ny || k < g.kmin() || k >= g.nz) continue;
      diag[u] += 1;
      const int v = unknown(i, j, k);
      if (v >= 0) {
        nbr[u][static_cast<std::size_t>(d)] = v;
      } else {
        b[u] += stored(i, j, k);
        ++known;
      }
    }
  }
  if (known == 0) {
    char what[160];
    std::snprintf(what, sizeof what, " (a %s of half-size %.17g about (%.17g, %.17g, %.17g))", r.cube ? "cube" : "sphere",
                  r.half_size, r.centre[0], r.centre[1], r.centre[2]);
    throw Error(BHNSID_READER_ERR_FORMAT,
                path + ": the held region" + what + " covers the whole grid; nothing to fill it from");
  }

  // Conjugate gradients from zero to a relative residual of 1e-15 (round-off: the Python module
  // runs the same iteration and agrees to ~1e-14).
  std::vector<double> x(n, 0), res = b, p = b, ap(n);
  const double bnorm = std::sqrt(dot(b, b));
  double rr = dot(res, res);
  const std::size_t max_iterations = 4 * n + 100;
  for (std::size_t it = 0; bnorm > 0 && it < max_iterations; ++it) {
    for (std::size_t u = 0; u < n; ++u) {
      double s = diag[u] * p[u];
      for (int v : nbr[u])
        if (v >= 0) s -= p[static_cast<std::size_t>(v)];
      ap[u] = s;
    }
    const double alpha = rr / dot(p, ap);
    for (std::size_t u = 0; u < n; ++u) {
      x[u] += alpha * p[u];
      res[u] -= alpha * ap[u];
    }
    const double rr_new = dot(res, res);
    if (std::sqrt(rr_new) <= 1e-15 * bnorm) break;
    const double beta = rr_new / rr;
    rr = rr_new;
    for (std::size_t u = 0; u < n; ++u) p[u] = res[u] + beta * p[u];
  }

  std::size_t changed = 0;
  for (std::size_t u = 0; u < n; ++u) {
    const auto [i, j, k] = points[u];
    if (k < 0) continue;
    // An odd field vanishes on the symmetry plane; the solve gives that only to round-off.
    values[g.at(i, j, k)] = (g.equatorial && k == 0 && parity < 0) ? 0.0 : x[u];
    ++changed;
  }
  return changed;
}

}  // namespace bhnsid::reader
