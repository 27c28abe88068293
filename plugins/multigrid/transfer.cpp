#include "transfer.hpp"

#include <algorithm>
#include <vector>

#include "bhnsid/interfaces/stencil.hpp"

namespace bhnsid::multigrid {
namespace {

// Weight of the fine neighbour on side d (-1 or +1) of coarse index I along one axis. Next to a
// face whose rows are slaved to the interior (fold), the weight that full weighting would give to
// the coarse face point goes to the interior coarse point instead (vertex-centred Neumann-type
// folding); without it the V-cycle with Robin faces converged by only 0.4-0.7 per cycle.
inline double side_weight(int d, int I, int last, bool low_is_face, bool fold) {
  if (fold && ((d < 0 && I == 1 && low_is_face) || (d > 0 && I == last - 1))) return 0.5;
  return 0.25;
}

// Full weighting at coarse (I, J, K): separable weights 1/4, 1/2, 1/4 per axis.
// c = FW(f) - minus at coarse interior points (minus may be nullptr).
void full_weighting(const Level& fl, const Level& cl, const double* f, const double* minus, double* c, bool fold) {
  const int kc0 = cl.k_begin(), kc1 = cl.nz - 1;
#pragma omp parallel if (static_cast<long>(cl.size) >= stencil::parallel_min_points)
  {
    // Per thread: the fine plane weighted in z, then in y, leaving only the x sum per coarse point.
    std::vector<double> zrow(static_cast<std::size_t>(fl.nx)), yzrow(static_cast<std::size_t>(fl.nx));
#pragma omp for schedule(static)
    for (int kc = kc0; kc < kc1; ++kc) {
      const int k = 2 * kc;
      const double wkm = side_weight(-1, kc, cl.nz - 1, !cl.z_symmetry, fold);
      const double wkp = side_weight(+1, kc, cl.nz - 1, true, fold);
      for (int jc = 1; jc < cl.ny - 1; ++jc) {
        const int j = 2 * jc;
        for (int i = 0; i < fl.nx; ++i) yzrow[static_cast<std::size_t>(i)] = 0;
        for (int dj = -1; dj <= 1; ++dj) {
          const double wj = dj == 0 ? 0.5 : side_weight(dj, jc, cl.ny - 1, true, fold);
          const double* m = f + fl.at(0, j + dj, k - 1);
          const double* z0 = f + fl.at(0, j + dj, k);
          const double* p = f + fl.at(0, j + dj, k + 1);
#pragma omp simd
          for (int i = 0; i < fl.nx; ++i) zrow[static_cast<std::size_t>(i)] = wkm * m[i] + wkp * p[i] + 0.5 * z0[i];
#pragma omp simd
          for (int i = 0; i < fl.nx; ++i) yzrow[static_cast<std::size_t>(i)] += wj * zrow[static_cast<std::size_t>(i)];
        }
        double* out = c + cl.at(0, jc, kc);
        const double* sub = minus ? minus + cl.at(0, jc, kc) : nullptr;
        for (int ic = 1; ic < cl.nx - 1; ++ic) {
          const int i = 2 * ic;
          const double v = side_weight(-1, ic, cl.nx - 1, true, fold) * yzrow[static_cast<std::size_t>(i - 1)] +
                           side_weight(+1, ic, cl.nx - 1, true, fold) * yzrow[static_cast<std::size_t>(i + 1)] +
                           0.5 * yzrow[static_cast<std::size_t>(i)];
          out[ic] = sub ? v - sub[ic] : v;
        }
      }
    }
  }
}

}  // namespace

void restrict_full_weighting_minus(const Level& fine, const Level& coarse, const double* f, const double* minus,
                                   double* c, bool fold_faces) {
  full_weighting(fine, coarse, f, minus, c, fold_faces);
}

void restrict_injection(const Level& fine, const Level& coarse, const double* f, double* c, double* copy) {
#pragma omp parallel for schedule(static) if (static_cast<long>(coarse.size) >= stencil::parallel_min_points)
  for (int kc = 0; kc < coarse.nz; ++kc)
    for (int jc = 0; jc < coarse.ny; ++jc) {
      const double* src = f + fine.at(0, 2 * jc, 2 * kc);
      double* dst = c + coarse.at(0, jc, kc);
      for (int ic = 0; ic < coarse.nx; ++ic) dst[ic] = src[2 * ic];
      if (copy) {
        double* again = copy + coarse.at(0, jc, kc);
        for (int ic = 0; ic < coarse.nx; ++ic) again[ic] = dst[ic];
      }
    }
}

void restrict_full_weighting(const Level& fine, const Level& coarse, const double* f, double* c) {
  restrict_injection(fine, coarse, f, c);
  full_weighting(fine, coarse, f, nullptr, c, false);
}

void prolong_correction(const Level& cl, const Level& fl, const double* c, const double* c_old, double* f,
                        const std::uint8_t* fixed, bool faces) {
  const int k0 = faces ? 0 : fl.k_begin();
  const int k1 = faces ? fl.nz : fl.nz - 1;
  const int j0 = faces ? 0 : 1, j1 = faces ? fl.ny : fl.ny - 1;
  const int i0 = faces ? 0 : 1, i1 = faces ? fl.nx : fl.nx - 1;
#pragma omp parallel if (static_cast<long>(fl.size) >= stencil::parallel_min_points)
  {
    std::vector<double> row(static_cast<std::size_t>(cl.nx));
#pragma omp for schedule(static)
    for (int k = k0; k < k1; ++k) {
      const int kc = k / 2, kodd = k & 1;
      for (int j = j0; j < j1; ++j) {
        const int jc = j / 2, jodd = j & 1;
        // The coarse correction interpolated to (y_j, z_k) along the whole coarse row.
        auto corr = [&](int jj, int kk) {
          const double* a = c + cl.at(0, jj, kk);
          const double* b = c_old + cl.at(0, jj, kk);
          return [a, b](int ic) { return a[ic] - b[ic]; };
        };
        const auto e00 = corr(jc, kc);
        if (!jodd && !kodd) {
          for (int ic = 0; ic < cl.nx; ++ic) row[static_cast<std::size_t>(ic)] = e00(ic);
        } else if (jodd && !kodd) {
          const auto e10 = corr(jc + 1, kc);
          for (int ic = 0; ic < cl.nx; ++ic) row[static_cast<std::size_t>(ic)] = 0.5 * (e00(ic) + e10(ic));
        } else if (!jodd && kodd) {
          const auto e01 = corr(jc, kc + 1);
          for (int ic = 0; ic < cl.nx; ++ic) row[static_cast<std::size_t>(ic)] = 0.5 * (e00(ic) + e01(ic));
        } else {
          const auto e10 = corr(jc + 1, kc), e01 = corr(jc, kc + 1), e11 = corr(jc + 1, kc + 1);
          for (int ic = 0; ic < cl.nx; ++ic)
            row[static_cast<std::size_t>(ic)] = 0.25 * (e00(ic) + e10(ic) + e01(ic) + e11(ic));
        }
        double* out = f + fl.at(0, j, k);
        const std::uint8_t* held = fixed ? fixed + fl.at(0, j, k) : nullptr;
        const bool face_row = j == 0 || j == fl.ny - 1 || k == fl.nz - 1 || (k == 0 && !fl.z_symmetry);
        const int ib = face_row ? 0 : i0, ie = face_row ? fl.nx : i1;
        const double* r = row.data();
        if (!held) {
          // Even fine points sit on coarse points, odd ones halfway: two branch-free passes.
          for (int i = ib + (ib & 1); i < ie; i += 2) out[i] += r[i / 2];
          for (int i = ib | 1; i < ie; i += 2) out[i] += 0.5 * (r[i / 2] + r[i / 2 + 1]);
        } else {
          // The same with the held points selected away (not branched over: the loops vectorise).
          for (int i = ib + (ib & 1); i < ie; i += 2) out[i] += held[i] ? 0.0 : r[i / 2];
          for (int i = ib | 1; i < ie; i += 2) out[i] += held[i] ? 0.0 : 0.5 * (r[i / 2] + r[i / 2 + 1]);
        }
      }
    }
  }
}

}  // namespace bhnsid::multigrid

namespace bhnsid::multigrid {
namespace {

// Coarse points and weights that give fine index `i` along an axis with `last` the last coarse index.
struct AxisWeights {
  int first = 0, count = 1;
  double w[4] = {1, 0, 0, 0};
};

AxisWeights axis_weights(int i, int last) {
  AxisWeights a;
  const int I = i / 2;
  if ((i & 1) == 0) {
    a.first = I;
    return a;
  }
  if (I - 1 >= 0 && I + 2 <= last) {
    a.first = I - 1;
    a.count = 4;
    a.w[0] = a.w[3] = -1.0 / 16;
    a.w[1] = a.w[2] = 9.0 / 16;
  } else {
    a.first = I;
    a.count = 2;
    a.w[0] = a.w[1] = 0.5;
  }
  return a;
}

}  // namespace

void prolong_correction_cubic(const Level& cl, const Level& fl, const double* c, const double* c_old, double* f,
                              const std::uint8_t* fixed, bool faces) {
  const int k0 = faces ? 0 : fl.k_begin(), k1 = faces ? fl.nz : fl.nz - 1;
  const std::size_t plane_size = static_cast<std::size_t>(cl.nx) * static_cast<std::size_t>(cl.ny);
#pragma omp parallel if (static_cast<long>(fl.size) >= stencil::parallel_min_points)
  {
    std::vector<double> plane(plane_size), row(static_cast<std::size_t>(cl.nx));
#pragma omp for schedule(static)
    for (int k = k0; k < k1; ++k) {
      const AxisWeights wz = axis_weights(k, cl.nz - 1);
      const int nx = cl.nx;
      // Row by row, one coarse plane (or row) at a time: unit-stride loops that vectorise.
      for (int J = 0; J < cl.ny; ++J) {
        double* pl = plane.data() + static_cast<std::size_t>(J) * static_cast<std::size_t>(nx);
        for (int I = 0; I < nx; ++I) pl[I] = 0;
        for (int t = 0; t < wz.count; ++t) {
          const double *a = c + cl.at(0, J, wz.first + t), *b = c_old + cl.at(0, J, wz.first + t), w = wz.w[t];
#pragma omp simd
          for (int I = 0; I < nx; ++I) pl[I] += w * (a[I] - b[I]);
        }
      }
      const bool face_plane = k == fl.nz - 1 || (k == 0 && !fl.z_symmetry);
      for (int j = 0; j < fl.ny; ++j) {
        const bool face_row = face_plane || j == 0 || j == fl.ny - 1;
        if (face_row && !faces) continue;
        const AxisWeights wy = axis_weights(j, cl.ny - 1);
        double* r = row.data();
        for (int I = 0; I < nx; ++I) r[I] = 0;
        for (int t = 0; t < wy.count; ++t) {
          const double* pl = plane.data() + static_cast<std::size_t>(wy.first + t) * static_cast<std::size_t>(nx);
          const double w = wy.w[t];
#pragma omp simd
          for (int I = 0; I < nx; ++I) r[I] += w * pl[I];
        }
        double* out = f + fl.at(0, j, k);
        const std::uint8_t* held = fixed ? fixed + fl.at(0, j, k) : nullptr;
        const int ib = (face_row || faces) ? 0 : 1, ie = (face_row || faces) ? fl.nx : fl.nx - 1;
        auto add = [&](int i, double e) { out[i] += held && held[i] ? 0.0 : e; };
        // Along x: even points on coarse points; odd ones cubic (-1, 9, 9, -1)/16 where the four
        // coarse points exist, linear next to the ends (axis_weights).
        const int last = nx - 1;
        for (int i = ib + (ib & 1); i < ie; i += 2) add(i, r[i / 2]);
        auto linear = [&](int i) { add(i, 0.5 * (r[i / 2] + r[i / 2 + 1])); };
        // Odd i with 1 <= i/2 <= last - 2 take the cubic: i in [3, 2 last - 2).
        const int odd0 = ib | 1, cubic0 = std::max(odd0, 3), cubic1 = std::min(ie, 2 * last - 2);
        for (int i = odd0; i < std::min(cubic0, ie); i += 2) linear(i);
        for (int i = cubic0; i < cubic1; i += 2) {
          const int I = i / 2;
          add(i, (9.0 * (r[I] + r[I + 1]) - (r[I - 1] + r[I + 2])) / 16.0);
        }
        for (int i = std::max(cubic1 | 1, odd0); i < ie; i += 2) linear(i);
      }
    }
  }
}

}  // namespace bhnsid::multigrid
