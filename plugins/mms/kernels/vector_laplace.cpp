#include "kernels/vector_laplace.hpp"

#include <Eigen/Dense>

#include "bhnsid/interfaces/stencil.hpp"

namespace bhnsid::mms::kernels {

namespace {

// Point values are passed as this struct, never as a double[3]: GCC 12 does not vectorise an
// omp simd loop that writes a local array through a pointer.
struct Triple {
  double x, y, z;
};

// One component's row and the eight rows around it that the stencil reads. With a base pointer per
// row every access is p[i] or p[i +- 1]; GCC 12 gives up vectorising a loop that mixes f[i + 1 + sy]
// with f[i + sy + sz].
struct Rows {
  const double *c, *ym, *yp, *zm, *zp, *ymzm, *ymzp, *ypzm, *ypzp;
};

Rows rows_at(const double* f, std::ptrdiff_t sy, std::ptrdiff_t sz) {
  return {f, f - sy, f + sy, f - sz, f + sz, f - sy - sz, f - sy + sz, f + sy - sz, f + sy + sz};
}

// h^2 (lap V^a + (1/3) d^a d_j V^j) at point i of the rows. Forced inline: a call in the loop
// body would keep the point loops from vectorising.
[[gnu::always_inline]] inline Triple principal(const Rows& x, const Rows& y, const Rows& z, int i) {
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

// Everything one row of either kernel reads: V around the row, s, rhs, n's y and z, and the
// constants; copied into the loop's own frame so that nothing is reloaded per point.
template <bool HasRhs>
struct Row {
  Rows x, y, z;
  const double *sx, *sy, *sz;
  const double *fx = nullptr, *fy = nullptr, *fz = nullptr;
  double ny = 0, nz = 0;
  double ih2 = 0, kappa = 0;
  double nx0 = 0, dnx = 0;  // n^x = nx0 + dnx i along the row

  double nx(int i) const { return nx0 + dnx * i; }

  // L(V) - rhs at point i.
  [[gnu::always_inline]] Triple residual(int i) const {
    const Triple l = principal(x, y, z, i);
    const double n_x = nx(i);
    const double kn = kappa * (n_x * x.c[i] + ny * y.c[i] + nz * z.c[i]);
    Triple r{ih2 * l.x - kn * n_x + sx[i], ih2 * l.y - kn * ny + sy[i], ih2 * l.z - kn * nz + sz[i]};
    if constexpr (HasRhs) {
      r.x -= fx[i];
      r.y -= fy[i];
      r.z -= fz[i];
    }
    return r;
  }
};

template <bool HasRhs>
Row<HasRhs> row_at(const Level& lv, ConstComponents v, ConstComponents s, const double* const* rhs, double kappa,
                   int j, int k) {
  const std::ptrdiff_t p = lv.at(0, j, k);
  const double inv_rc = 1.0 / lv.half_width();
  Row<HasRhs> row{rows_at(v[0] + p, lv.sy, lv.sz), rows_at(v[1] + p, lv.sy, lv.sz), rows_at(v[2] + p, lv.sy, lv.sz),
                  s[0] + p, s[1] + p, s[2] + p};
  if constexpr (HasRhs) {
    row.fx = rhs[0] + p;
    row.fy = rhs[1] + p;
    row.fz = rhs[2] + p;
  }
  row.ny = lv.y(j) * inv_rc;
  row.nz = lv.z(k) * inv_rc;
  row.ih2 = stencil::inv_h2(lv);
  row.kappa = kappa;
  row.nx0 = lv.origin[0] * inv_rc;
  row.dnx = lv.dx * inv_rc;
  return row;
}

template <bool HasRhs, bool Masked>
void residual_rows(const Level& lv, ConstComponents v, ConstComponents s, double kappa, const double* const* rhs,
                   const std::uint8_t* fixed, Components out) {
  const int end = lv.nx - 1;
  stencil::for_interior_rows(lv, [&](int j, int k) {
    const Row<HasRhs> row = row_at<HasRhs>(lv, v, s, rhs, kappa, j, k);
    const std::ptrdiff_t p = lv.at(0, j, k);
    double *ox = out[0] + p, *oy = out[1] + p, *oz = out[2] + p;
    [[maybe_unused]] const std::uint8_t* m = fixed + p;
#pragma omp simd
    for (int i = 1; i < end; ++i) {
      const Triple r = row.residual(i);
      double keep = 1.0;
      if constexpr (Masked) keep = m[i] ? 0.0 : 1.0;
      ox[i] = -keep * r.x;
      oy[i] = -keep * r.y;
      oz[i] = -keep * r.z;
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
  const double diagonal = -(20.0 / 3.0) * stencil::inv_h2(lv);  // -6/h^2 from lap V^a, -(1/3) 2/h^2 from d_a d_a V^a
  const int end = lv.nx - 1, j1 = lv.ny - 1;
  const ConstComponents vc{v[0], v[1], v[2]};
  auto plane = [&](int k, int colour) {
    for (int j = 1; j < j1; ++j) {
      const Row<HasRhs> row = row_at<HasRhs>(lv, vc, s, rhs, kappa, j, k);
      const std::ptrdiff_t p = lv.at(0, j, k);
      double *x = v[0] + p, *y = v[1] + p, *z = v[2] + p;
      [[maybe_unused]] const std::uint8_t* m = fixed + p;
      const int first = stencil::first_of_colour(j, k, colour);
      if constexpr (Coupled) {
        for (int i = first; i < end; i += 2) {
          if constexpr (Masked)
            if (m[i]) continue;
          const Triple r = row.residual(i);
          const Eigen::Vector3d n(row.nx(i), row.ny, row.nz);
          const Eigen::Matrix3d jac = diagonal * Eigen::Matrix3d::Identity() - kappa * n * n.transpose();
          const Eigen::Vector3d step = jac.partialPivLu().solve(Eigen::Vector3d(r.x, r.y, r.z));
          x[i] -= omega * step[0];
          y[i] -= omega * step[1];
          z[i] -= omega * step[2];
        }
      } else {
        const double factor = -omega / diagonal;
        // Within a row the colour's points read only the other colour: independent iterations.
#pragma omp simd
        for (int i = first; i < end; i += 2) {
          const Triple r = row.residual(i);
          double g = factor;
          if constexpr (Masked) g = m[i] ? 0.0 : factor;
          x[i] += g * r.x;
          y[i] += g * r.y;
          z[i] += g * r.z;
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
    // kappa = 0 keeps the point Jacobian diagonal: the branch-free, vectorised loop.
    if (kappa != 0)
      relax_sweep<true, r, m>(lv, v, source, kappa, rhs, fixed, omega, mirror);
    else
      relax_sweep<false, r, m>(lv, v, source, kappa, rhs, fixed, omega, mirror);
  });
}

}  // namespace bhnsid::mms::kernels
