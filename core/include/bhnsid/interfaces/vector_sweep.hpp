#pragma once
// The loops of every vector elliptic operator of the momentum-constraint / minimal-distortion form
//   L(V)^a = lap V^a + (1/3) d^a d_j V^j + N^a(x, V, dV),
// second-order centred differences, the mixed derivatives by the 4-point stencil
// (f(+a,+b) - f(+a,-b) - f(-a,+b) + f(-a,-b)) / 4h^2. The lower-order term N is supplied as a small
// struct (inlined; one tight loop per operator) that may read V's centred first derivatives but not
// V at the point itself, so that the point Jacobian stays -(20/3)/h^2 times the identity and the
// Gauss-Seidel update is a division:
//   struct Lower {
//     Triple at(std::ptrdiff_t idx, std::ptrdiff_t i, const Rows& x, const Rows& y, const Rows& z) const;
//   };
// (idx: the array index of the point; i: its index along the row; x, y, z: the rows of V's three
// components around it, see gradient()). The index along a row is 64-bit like the doubles: with an
// int index that the shift converts to a coordinate, GCC 12 vectorised 16 points per iteration
// (16 ints fill a 512-bit register), two registers per double value, and spilled; 8 points per
// iteration made the shift's sweep 7 % faster. A Lower that needs the row's coordinates (the shift's
// analytic puncture terms) also has `RowLower row(int j, int k) const`, an object with the same
// at(), bound once per row. Used by the momentum and shift plugins.
#include <array>
#include <cstddef>
#include <cstdint>

#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/scalar_sweep.hpp"
#include "bhnsid/interfaces/stencil.hpp"

namespace bhnsid::stencil {

// Point values travel as this struct, never as a double[3]: GCC 12 does not vectorise an omp simd
// loop that writes a local array through a pointer.
struct Triple {
  double x, y, z;
};

using ConstComponents = std::array<const double*, 3>;
using Components = std::array<double*, 3>;

// One component's row and the eight rows around it that the stencil reads. With a base pointer per
// row every access is p[i] or p[i +- 1]; GCC 12 gives up vectorising a loop that mixes f[i + 1 + sy]
// with f[i + sy + sz].
struct Rows {
  const double *c, *ym, *yp, *zm, *zp, *ymzm, *ymzp, *ypzm, *ypzp;
};

inline Rows rows_at(const double* f, std::ptrdiff_t sy, std::ptrdiff_t sz) {
  return {f, f - sy, f + sy, f - sz, f + sz, f - sy - sz, f - sy + sz, f + sy - sz, f + sy + sz};
}

/// h^2 (lap V^a + (1/3) d^a d_j V^j) at point i of the rows.
[[gnu::always_inline]] inline Triple principal(const Rows& x, const Rows& y, const Rows& z, std::ptrdiff_t i) {
  auto lap = [i](const Rows& f) {
    return f.c[i - 1] + f.c[i + 1] + f.ym[i] + f.yp[i] + f.zm[i] + f.zp[i] - 6.0 * f.c[i];
  };
  auto dxx = [i](const Rows& f) { return f.c[i - 1] + f.c[i + 1] - 2.0 * f.c[i]; };
  auto dyy = [i](const Rows& f) { return f.ym[i] + f.yp[i] - 2.0 * f.c[i]; };
  auto dzz = [i](const Rows& f) { return f.zm[i] + f.zp[i] - 2.0 * f.c[i]; };
  auto dxy = [i](const Rows& f) { return 0.25 * (f.yp[i + 1] - f.ym[i + 1] - f.yp[i - 1] + f.ym[i - 1]); };
  auto dxz = [i](const Rows& f) { return 0.25 * (f.zp[i + 1] - f.zm[i + 1] - f.zp[i - 1] + f.zm[i - 1]); };
  auto dyz = [i](const Rows& f) { return 0.25 * (f.ypzp[i] - f.ypzm[i] - f.ymzp[i] + f.ymzm[i]); };
  constexpr double third = 1.0 / 3.0;
  return {lap(x) + third * (dxx(x) + dxy(y) + dxz(z)), lap(y) + third * (dxy(x) + dyy(y) + dyz(z)),
          lap(z) + third * (dxz(x) + dyz(y) + dzz(z))};
}

/// (d_x f, d_y f, d_z f) at point i by centred differences; inv_2h = 1/(2h).
[[gnu::always_inline]] inline Triple gradient(const Rows& f, std::ptrdiff_t i, double inv_2h) {
  return {inv_2h * (f.c[i + 1] - f.c[i - 1]), inv_2h * (f.yp[i] - f.ym[i]), inv_2h * (f.zp[i] - f.zm[i])};
}

/// lower.row(j, k) where the Lower has one (see the top of this file), else lower itself.
template <class Lower>
[[gnu::always_inline]] inline decltype(auto) bind_row(const Lower& lower, int j, int k) {
  if constexpr (requires { lower.row(j, k); })
    return lower.row(j, k);
  else
    return (lower);
}

/// out^a = rhs^a - L(V)^a at every interior point (rhs nullptr: zero), 0 where fixed != 0.
template <bool HasRhs, bool Masked, class Lower>
void vector_residual(const Level& lv, ConstComponents v, const double* const* rhs, const std::uint8_t* fixed,
                     Components out, const Lower& lower) {
  const int end = lv.nx - 1;
  const double ih2 = inv_h2(lv);
  for_interior_rows(lv, [&](int j, int k) {
    const std::ptrdiff_t p = lv.at(0, j, k);
    const Rows x = rows_at(v[0] + p, lv.sy, lv.sz), y = rows_at(v[1] + p, lv.sy, lv.sz),
               z = rows_at(v[2] + p, lv.sy, lv.sz);
    double *ox = out[0] + p, *oy = out[1] + p, *oz = out[2] + p;
    [[maybe_unused]] const double *fx = nullptr, *fy = nullptr, *fz = nullptr;
    if constexpr (HasRhs) fx = rhs[0] + p, fy = rhs[1] + p, fz = rhs[2] + p;
    [[maybe_unused]] const std::uint8_t* m = fixed + p;
    const auto& row_lower = bind_row(lower, j, k);
    with_row_mask<Masked>(fixed, p, end, [&](auto masked_row) {
#pragma omp simd
      for (std::ptrdiff_t i = 1; i < end; ++i) {
        const Triple l = principal(x, y, z, i);
        const Triple n = row_lower.at(p + i, i, x, y, z);
        Triple r{-(ih2 * l.x + n.x), -(ih2 * l.y + n.y), -(ih2 * l.z + n.z)};
        if constexpr (HasRhs) r.x += fx[i], r.y += fy[i], r.z += fz[i];
        double keep = 1.0;
        if constexpr (decltype(masked_row)::value) keep = m[i] ? 0.0 : 1.0;
        ox[i] = keep * r.x;
        oy[i] = keep * r.y;
        oz[i] = keep * r.z;
      }
    });
  });
}

// The mixed derivatives couple a point to points of its own colour at (i+-1, j+-1, k),
// (i+-1, j, k+-1) and (i, j+-1, k+-1), so red_black_sweep, which relies on a colour reading only the
// other one, would let threads race on the planes their slabs share. Instead each colour is relaxed
// as two passes over the planes, even then odd (counted from k0): every even plane reads the odd
// planes as they were, every odd plane the even ones as they are now, and the Gauss-Seidel order
// within the colour is the same on any number of threads.
//
// The two passes run as one wavefront, odd plane k-1 right after even plane k, so that the planes
// around k are still in cache for the odd pass: the unknowns stream through memory once per colour
// instead of twice. The result is that of the two passes exactly, since an even plane reads no even
// plane and an odd plane is relaxed only after both its even neighbours. Each thread owns a slab of
// planes; it first relaxes the even planes at its slab's ends (the only ones another slab's odd
// planes read, and they read only odd planes, which nobody has touched yet), then, after a barrier,
// runs the wavefront through its slab.
/// Planes [k0, k1) of points_per_plane points each (default: every interior plane of the level). A
/// colour over fewer than 2 parallel_min_points points (the coarsest levels) runs on one thread. The
/// shift's box about the hole (about 1 800 points per pass at n = 128) and the level of n = 32
/// (7 700) run in parallel: on one thread they left the other idle for a tenth of the
/// eight-equation solve on 2 threads (with GOMP's default wait policy; under
/// OMP_WAIT_POLICY=passive each wake-up is a futex call and 2 threads are slower than 1 with any
/// threshold, docs/performance.md).
template <class PlaneFn>
void colour_in_two_passes(int k0, int k1, long points_per_plane, int colour, PlaneFn&& plane) {
  const int planes = k1 - k0;
  if (planes <= 0) return;
  const bool parallel = planes / 2 * points_per_plane >= parallel_min_points;
  auto even = [k0](int k) { return ((k - k0) & 1) == 0; };
#pragma omp parallel if (parallel)
  {
    const int nt = omp_get_num_threads(), t = omp_get_thread_num();
    const int a = k0 + static_cast<int>(static_cast<long>(planes) * t / nt);
    const int b = k0 + static_cast<int>(static_cast<long>(planes) * (t + 1) / nt);
    const bool first_even = a < b && even(a), last_even = b - 1 > a && even(b - 1);
    if (first_even) plane(a, colour);
    if (last_even) plane(b - 1, colour);
#pragma omp barrier
    for (int k = a; k <= b; ++k) {
      if (k < b && even(k) && !(k == a && first_even) && !(k == b - 1 && last_even)) plane(k, colour);
      if (k - 1 >= a && !even(k - 1)) plane(k - 1, colour);
    }
  }
}
template <class PlaneFn>
void colour_in_two_passes(const Level& lv, int colour, PlaneFn&& plane) {
  colour_in_two_passes(lv.k_begin(), lv.nz - 1, static_cast<long>(lv.nx - 2) * (lv.ny - 2), colour, plane);
}

/// A box of interior points, bounds inclusive.
struct Box {
  int i0, i1, j0, j1, k0, k1;
};

/// Every interior point of the level.
inline Box interior(const Level& lv) { return {1, lv.nx - 2, 1, lv.ny - 2, lv.k_begin(), lv.nz - 2}; }

/// One red-black Gauss-Seidel sweep (colour 0, then 1) toward L(V) = rhs on the box: at each
/// non-held point V^a += omega (L - rhs)^a h^2 / (20/3). mirror() refreshes the ghost plane of all
/// three components between the colours (equatorial symmetry, when the box reaches z = 0).
template <bool HasRhs, bool Masked, class Lower>
void vector_relax(const Level& lv, Components v, const double* const* rhs, const std::uint8_t* fixed, double omega,
                  const Mirror& mirror, const Lower& lower, const Box& box) {
  const double ih2 = inv_h2(lv);
  const double factor = omega / ((20.0 / 3.0) * ih2);  // -omega / (dL/dV), dL/dV = -(20/3)/h^2
  const int end = lv.nx - 1, i1 = box.i1 + 1;
  auto plane = [&](int k, int colour) {
    for (int j = box.j0; j <= box.j1; ++j) {
      const std::ptrdiff_t p = lv.at(0, j, k);
      const Rows x = rows_at(v[0] + p, lv.sy, lv.sz), y = rows_at(v[1] + p, lv.sy, lv.sz),
                 z = rows_at(v[2] + p, lv.sy, lv.sz);
      double *vx = v[0] + p, *vy = v[1] + p, *vz = v[2] + p;
      [[maybe_unused]] const double *fx = nullptr, *fy = nullptr, *fz = nullptr;
      if constexpr (HasRhs) fx = rhs[0] + p, fy = rhs[1] + p, fz = rhs[2] + p;
      [[maybe_unused]] const std::uint8_t* m = fixed + p;
      const auto& row_lower = bind_row(lower, j, k);
      with_row_mask<Masked>(fixed, p, end, [&](auto masked_row) {
        // Within a row the colour's points read only the other colour: independent iterations.
#pragma omp simd
        for (std::ptrdiff_t i = box.i0 + ((box.i0 + j + k + colour) & 1); i < i1; i += 2) {
          const Triple l = principal(x, y, z, i);
          const Triple n = row_lower.at(p + i, i, x, y, z);
          Triple r{ih2 * l.x + n.x, ih2 * l.y + n.y, ih2 * l.z + n.z};
          if constexpr (HasRhs) r.x -= fx[i], r.y -= fy[i], r.z -= fz[i];
          double g = factor;
          if constexpr (decltype(masked_row)::value) g = m[i] ? 0.0 : factor;
          vx[i] += g * r.x;
          vy[i] += g * r.y;
          vz[i] += g * r.z;
        }
      });
    }
  };
  const long points_per_plane = static_cast<long>(box.i1 - box.i0 + 1) * (box.j1 - box.j0 + 1);
  colour_in_two_passes(box.k0, box.k1 + 1, points_per_plane, 0, plane);
  if (lv.z_symmetry && box.k0 == lv.k_begin()) mirror();
  colour_in_two_passes(box.k0, box.k1 + 1, points_per_plane, 1, plane);
}

template <class Lower>
void vector_residual_any(const Level& lv, ConstComponents v, const double* const* rhs, const std::uint8_t* fixed,
                         Components out, const Lower& lower) {
  with_variants(rhs != nullptr, fixed != nullptr, [&](auto has_rhs, auto masked) {
    vector_residual<decltype(has_rhs)::value, decltype(masked)::value>(lv, v, rhs, fixed, out, lower);
  });
}

template <class Lower>
void vector_relax_any(const Level& lv, Components v, const double* const* rhs, const std::uint8_t* fixed,
                      double omega, const Mirror& mirror, const Lower& lower, const Box& box) {
  with_variants(rhs != nullptr, fixed != nullptr, [&](auto has_rhs, auto masked) {
    vector_relax<decltype(has_rhs)::value, decltype(masked)::value>(lv, v, rhs, fixed, omega, mirror, lower, box);
  });
}
template <class Lower>
void vector_relax_any(const Level& lv, Components v, const double* const* rhs, const std::uint8_t* fixed,
                      double omega, const Mirror& mirror, const Lower& lower) {
  vector_relax_any(lv, v, rhs, fixed, omega, mirror, lower, interior(lv));
}

}  // namespace bhnsid::stencil
