#include "kernels/vector_laplace.hpp"

#include <Eigen/Dense>

#include "bhnsid/interfaces/stencil.hpp"
#include "bhnsid/interfaces/vector_sweep.hpp"

namespace bhnsid::mms::kernels {

namespace {

using stencil::colour_in_two_passes;
using stencil::principal;
using stencil::Rows;
using stencil::rows_at;
using stencil::Triple;

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
