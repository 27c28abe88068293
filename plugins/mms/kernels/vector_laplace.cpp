#include "kernels/vector_laplace.hpp"

#include <Eigen/Dense>

#include "bhnsid/interfaces/stencil.hpp"

namespace bhnsid::mms::kernels {

namespace {

struct Strides {
  std::ptrdiff_t y, z;
};

// h^2 (lap V^a + (1/3) d^a d_j V^j) at offset i of the rows x, y, z (the components). Forced
// inline: a call in the loop body would keep the point loops from vectorising.
[[gnu::always_inline]] inline void principal(const double* x, const double* y, const double* z, std::ptrdiff_t i, Strides s,
                      double out[3]) {
  const std::ptrdiff_t sy = s.y, sz = s.z;
  auto lap = [i, sy, sz](const double* f) {
    return f[i - 1] + f[i + 1] + f[i - sy] + f[i + sy] + f[i - sz] + f[i + sz] - 6.0 * f[i];
  };
  auto second = [i](const double* f, std::ptrdiff_t a) { return f[i - a] + f[i + a] - 2.0 * f[i]; };
  auto mixed = [i](const double* f, std::ptrdiff_t a, std::ptrdiff_t b) {
    return 0.25 * (f[i + a + b] - f[i + a - b] - f[i - a + b] + f[i - a - b]);
  };
  const double gx = second(x, 1) + mixed(y, 1, sy) + mixed(z, 1, sz);
  const double gy = mixed(x, 1, sy) + second(y, sy) + mixed(z, sy, sz);
  const double gz = mixed(x, 1, sz) + mixed(y, sy, sz) + second(z, sz);
  constexpr double third = 1.0 / 3.0;
  out[0] = lap(x) + third * gx;
  out[1] = lap(y) + third * gy;
  out[2] = lap(z) + third * gz;
}

// Everything a row of either kernel needs: the rows of V, s and rhs, and n's y and z.
template <bool HasRhs>
struct Row {
  const double *x, *y, *z, *sx, *sy, *sz;
  const double *fx = nullptr, *fy = nullptr, *fz = nullptr;
  double ny = 0, nz = 0;

  // L(V) - rhs at point i; nx is n's x component there.
  [[gnu::always_inline]] void residual(std::ptrdiff_t i, Strides st, double ih2, double kappa, double nx, double r[3]) const {
    principal(x, y, z, i, st, r);
    const double kn = kappa * (nx * x[i] + ny * y[i] + nz * z[i]);
    r[0] = ih2 * r[0] - kn * nx + sx[i];
    r[1] = ih2 * r[1] - kn * ny + sy[i];
    r[2] = ih2 * r[2] - kn * nz + sz[i];
    if constexpr (HasRhs) {
      r[0] -= fx[i];
      r[1] -= fy[i];
      r[2] -= fz[i];
    }
  }
};

template <bool HasRhs>
Row<HasRhs> row_at(const Level& lv, ConstComponents v, ConstComponents s, const double* const* rhs, int j, int k) {
  const std::ptrdiff_t p = lv.at(0, j, k);
  const double inv_rc = 1.0 / lv.half_width();
  Row<HasRhs> row{v[0] + p, v[1] + p, v[2] + p, s[0] + p, s[1] + p, s[2] + p};
  if constexpr (HasRhs) {
    row.fx = rhs[0] + p;
    row.fy = rhs[1] + p;
    row.fz = rhs[2] + p;
  }
  row.ny = lv.y(j) * inv_rc;
  row.nz = lv.z(k) * inv_rc;
  return row;
}

template <bool HasRhs, bool Masked>
void residual_rows(const Level& lv, ConstComponents v, ConstComponents s, double kappa, const double* const* rhs,
                   const std::uint8_t* fixed, Components out) {
  const Strides st{lv.sy, lv.sz};
  const double ih2 = stencil::inv_h2(lv), inv_rc = 1.0 / lv.half_width();
  // n^x = x / r_c along the row, from locals: reading the Level inside the loop blocks vectorising.
  const double nx0 = lv.origin[0] * inv_rc, dnx = lv.dx * inv_rc;
  const int end = lv.nx - 1;
  stencil::for_interior_rows(lv, [&](int j, int k) {
    const Row<HasRhs> row = row_at<HasRhs>(lv, v, s, rhs, j, k);
    const std::ptrdiff_t p = lv.at(0, j, k);
    double *ox = out[0] + p, *oy = out[1] + p, *oz = out[2] + p;
    // Values read through the closure inside the loop would be reloaded per point (the stores
    // might alias them) and keep it from vectorising; locals are registers.
    const Strides st_ = st;
    const double ih2_ = ih2, kappa_ = kappa, nx0_ = nx0, dnx_ = dnx;
    const int end_ = end;
#pragma omp simd
    for (int i = 1; i < end_; ++i) {
      double r[3];
      row.residual(i, st_, ih2_, kappa_, nx0_ + dnx_ * i, r);
      if constexpr (Masked)
        if (fixed[p + i]) r[0] = r[1] = r[2] = 0.0;
      ox[i] = -r[0];
      oy[i] = -r[1];
      oz[i] = -r[2];
    }
  });
}

// The mixed derivatives couple a point to points of its own colour at (i+-1, j+-1, k),
// (i+-1, j, k+-1) and (i, j+-1, k+-1), so stencil::red_black_sweep, which relies on a colour
// reading only the other one, would let threads race on the planes their slabs share. Instead each
// colour runs in two passes over the planes, even then odd (counted from k_begin): no plane is
// written while a neighbour reads it, and the Gauss-Seidel order within the colour is the same on
// any number of threads. The price is four passes over memory per sweep instead of one; the
// benchmark times the scalar kernels.
template <class PlaneFn>
void colour_in_two_passes(const Level& lv, int colour, PlaneFn&& plane) {
  const int k0 = lv.k_begin(), k1 = lv.nz - 1;
  for (int pass = 0; pass < 2; ++pass) {
#pragma omp parallel for schedule(static)
    for (int k = k0 + pass; k < k1; k += 2) plane(k, colour);
  }
}

template <bool Coupled, bool HasRhs, bool Masked>
void relax_sweep(const Level& lv, Components v, ConstComponents s, double kappa, const double* const* rhs,
                 const std::uint8_t* fixed, double omega, const Mirror& mirror) {
  const Strides st{lv.sy, lv.sz};
  const double ih2 = stencil::inv_h2(lv), inv_rc = 1.0 / lv.half_width();
  const double diagonal = -(20.0 / 3.0) * ih2;  // -6/h^2 from lap V^a, -(1/3) 2/h^2 from d_a d_a V^a
  const double nx0 = lv.origin[0] * inv_rc, dnx = lv.dx * inv_rc;
  const int end = lv.nx - 1, j1 = lv.ny - 1;
  const ConstComponents vc{v[0], v[1], v[2]};
  auto plane = [&](int k, int colour) {
    for (int j = 1; j < j1; ++j) {
      const Row<HasRhs> row = row_at<HasRhs>(lv, vc, s, rhs, j, k);
      const std::ptrdiff_t p = lv.at(0, j, k);
      double *x = v[0] + p, *y = v[1] + p, *z = v[2] + p;
      const int first = stencil::first_of_colour(j, k, colour);
      if constexpr (Coupled) {
        for (int i = first; i < end; i += 2) {
          if constexpr (Masked)
            if (fixed[p + i]) continue;
          const double nx = nx0 + dnx * i;
          double r[3];
          row.residual(i, st, ih2, kappa, nx, r);
          const Eigen::Vector3d n(nx, row.ny, row.nz);
          const Eigen::Matrix3d jac = diagonal * Eigen::Matrix3d::Identity() - kappa * n * n.transpose();
          const Eigen::Vector3d step = jac.partialPivLu().solve(Eigen::Vector3d(r[0], r[1], r[2]));
          x[i] -= omega * step[0];
          y[i] -= omega * step[1];
          z[i] -= omega * step[2];
        }
      } else {
        const double factor = -omega / diagonal;
        // Within a row the colour's points read only the other colour: independent iterations.
#pragma omp simd
        for (int i = first; i < end; i += 2) {
          double r[3];
          row.residual(i, st, ih2, 0.0, nx0 + dnx * i, r);
          double g = factor;
          if constexpr (Masked) g = fixed[p + i] ? 0.0 : factor;
          x[i] += g * r[0];
          y[i] += g * r[1];
          z[i] += g * r[2];
        }
      }
    }
  };
  colour_in_two_passes(lv, 0, plane);
  if (lv.z_symmetry) mirror();
  colour_in_two_passes(lv, 1, plane);
}

}  // namespace

void vector_residual(const Level& lv, ConstComponents v, ConstComponents source, double kappa,
                     const double* const* rhs, const std::uint8_t* fixed, Components out) {
  with_variants(rhs != nullptr, fixed != nullptr, [&](auto has_rhs, auto masked) {
    residual_rows<decltype(has_rhs)::value, decltype(masked)::value>(lv, v, source, kappa, rhs, fixed, out);
  });
}

void vector_relax(const Level& lv, Components v, ConstComponents source, double kappa, const double* const* rhs,
                  const std::uint8_t* fixed, double omega, const Mirror& mirror) {
  with_variants(rhs != nullptr, fixed != nullptr, [&](auto has_rhs, auto masked) {
    constexpr bool r = decltype(has_rhs)::value, m = decltype(masked)::value;
    if (kappa != 0)
      relax_sweep<true, r, m>(lv, v, source, kappa, rhs, fixed, omega, mirror);
    else
      relax_sweep<false, r, m>(lv, v, source, kappa, rhs, fixed, omega, mirror);
  });
}

}  // namespace bhnsid::mms::kernels
