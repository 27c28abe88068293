#pragma once
// The loops of every scalar elliptic operator L(u) = lap u + N(x, u): the 7-point Laplacian plus a
// point-local term N supplied as a small struct (inlined, so each operator compiles to its own
// tight loop):
//   struct Local {
//     static constexpr bool linear;                      // dN/du == 0: the Newton step needs no division
//     LocalTerm at(std::ptrdiff_t idx, double u) const;  // N and dN/du at array index idx
//   };
// The relaxation uses stencil::red_black_sweep: both colours fused plane by plane, each point moved
// by omega times its Newton step -(L - rhs) / (dL/du), dL/du = -6/h^2 + dN/du. Shared by every
// scalar equation plugin (hamiltonian, lapse, mms), so it lives with the other stencil scaffolding.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <type_traits>

#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/stencil.hpp"

namespace bhnsid::stencil {

/// Refreshes the ghost plane k = -1 of the unknown(s) being relaxed from plane 1 (equatorial
/// symmetry); the equation passes Grid::fill_ghosts, a test its own copy. Called once per sweep,
/// between the colours, so a std::function costs nothing that matters.
using Mirror = std::function<void()>;

/// Calls fn(std::bool_constant<has_rhs>{}, std::bool_constant<masked>{}).
template <class Fn>
void with_variants(bool has_rhs, bool masked, Fn&& fn) {
  if (has_rhs) {
    if (masked)
      fn(std::true_type{}, std::true_type{});
    else
      fn(std::true_type{}, std::false_type{});
  } else {
    if (masked)
      fn(std::false_type{}, std::true_type{});
    else
      fn(std::false_type{}, std::false_type{});
  }
}



struct LocalTerm {
  double value;  ///< N(x, u)
  double slope;  ///< dN/du
};

/// out = rhs - L(u) at every interior point (rhs nullptr: zero), 0 at held points.
template <bool HasRhs, bool Masked, class Local>
void scalar_residual(const Level& lv, const double* u, const double* rhs, const std::uint8_t* fixed, double* out,
                     const Local& local) {
  const std::ptrdiff_t sy = lv.sy, sz = lv.sz;
  const double ih2 = stencil::inv_h2(lv);
  const int end = lv.nx - 1;
  stencil::for_interior_rows(lv, [&](int j, int k) {
    const std::ptrdiff_t p = lv.at(0, j, k);
    const double* __restrict c = u + p;
    double* __restrict o = out + p;
    stencil::with_row_mask<Masked>(fixed, p, end, [&](auto masked_row) {
#pragma omp simd
      for (int i = 1; i < end; ++i) {
        double r = -(ih2 * (c[i - 1] + c[i + 1] + c[i - sy] + c[i + sy] + c[i - sz] + c[i + sz] - 6.0 * c[i]) +
                     local.at(p + i, c[i]).value);
        if constexpr (HasRhs) r += rhs[p + i];
        if constexpr (decltype(masked_row)::value) r = fixed[p + i] ? 0.0 : r;
        o[i] = r;
      }
    });
  });
}

template <bool HasRhs, bool Masked, class Local>
void scalar_relax(const Level& lv, double* u, const double* rhs, const std::uint8_t* fixed, double omega,
                  const Mirror& mirror, const Local& local) {
  const std::ptrdiff_t sy = lv.sy, sz = lv.sz;
  const double ih2 = stencil::inv_h2(lv);
  const double linear_factor = omega * lv.dx * lv.dx / 6.0;  // -omega / (dL/du) when dN/du = 0
  const int end = lv.nx - 1, j1 = lv.ny - 1;
  auto plane = [&](int k, int colour) {
    for (int j = 1; j < j1; ++j) {
      const std::ptrdiff_t p = lv.at(0, j, k);
      double* c = u + p;
      stencil::with_row_mask<Masked>(fixed, p, end, [&](auto masked_row) {
        // A point of one colour reads only points of the other, so the iterations are independent.
#pragma omp simd
        for (int i = stencil::first_of_colour(j, k, colour); i < end; i += 2) {
          const LocalTerm t = local.at(p + i, c[i]);
          double r =
              ih2 * (c[i - 1] + c[i + 1] + c[i - sy] + c[i + sy] + c[i - sz] + c[i + sz] - 6.0 * c[i]) + t.value;
          if constexpr (HasRhs) r -= rhs[p + i];
          double step;
          if constexpr (Local::linear)
            step = linear_factor * r;
          else
            step = -omega * r / (t.slope - 6.0 * ih2);
          if constexpr (decltype(masked_row)::value) step = fixed[p + i] ? 0.0 : step;
          c[i] += step;
        }
      });
    }
  };
  stencil::red_black_sweep(lv, plane, mirror);
}

/// The variants chosen at run time from whether rhs and fixed are null.
template <class Local>
void scalar_residual_any(const Level& lv, const double* u, const double* rhs, const std::uint8_t* fixed, double* out,
                         const Local& local) {
  with_variants(rhs != nullptr, fixed != nullptr, [&](auto has_rhs, auto masked) {
    scalar_residual<decltype(has_rhs)::value, decltype(masked)::value>(lv, u, rhs, fixed, out, local);
  });
}

template <class Local>
void scalar_relax_any(const Level& lv, double* u, const double* rhs, const std::uint8_t* fixed, double omega,
                      const Mirror& mirror, const Local& local) {
  with_variants(rhs != nullptr, fixed != nullptr, [&](auto has_rhs, auto masked) {
    scalar_relax<decltype(has_rhs)::value, decltype(masked)::value>(lv, u, rhs, fixed, omega, mirror, local);
  });
}

}  // namespace bhnsid::stencil
