#include "boundary_rows.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <type_traits>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/interfaces/stencil.hpp"

namespace bhnsid::multigrid {

namespace {

/// One face point's row: at most two planes of 3 x 3 points.
struct Row {
  int count = 0;
  double scale = 0;
  std::array<std::ptrdiff_t, 18> index;
  std::array<double, 18> weight;
};

/// The row of face point (i, j, k).
Row row_of(const Level& lv, const std::array<double, 3>& about, bool two_point, bool coarse, int i, int j, int k) {
  Row row;
  const int last[3] = {lv.nx - 1, lv.ny - 1, lv.nz - 1};
  const double xb[3] = {lv.x(i), lv.y(j), lv.z(k)};
  std::array<double, 3> centre = about;
  double X[3], reach = 0;
  for (int a = 0; a < 3; ++a) {
    X[a] = xb[a] - centre[a];
    reach = std::max(reach, std::fabs(X[a]));
  }
  // The ray needs a point one cell in (s > 0) with room around it; 1.5 cells keeps s >= 1/3 and lets
  // a centre just off the origin pass on a coarsest level of 4 intervals (face 2 cells away).
  if (reach < 1.5 * lv.dx && coarse) {
    // A coarse level carries only FAS corrections, and the finest level's rows (which the smoother
    // enforces) stay the condition: here a face point next to a centre near the face takes the row
    // about the centre moved out along the face's normal to 1.5 cells, still a 1/r fall-off.
    // Cutting the hierarchy instead left the paper's mu = 10 grids a 20,808-unknown direct solve;
    // holding the correction at such points (u - u_inf = rhs) converged by 0.29-0.36 per cycle
    // against 0.22-0.26 for this row (docs/performance.md).
    const bool on_face[3] = {i == 0 || i == last[0], j == 0 || j == last[1],
                             k == last[2] || (k == 0 && !lv.z_symmetry)};
    int normal = -1;
    for (int a = 0; a < 3; ++a)
      if (on_face[a] && (normal < 0 || std::fabs(X[a]) > std::fabs(X[normal]))) normal = a;
    X[normal] = (i == 0 && normal == 0) || (j == 0 && normal == 1) || (k == 0 && normal == 2) ? -1.5 * lv.dx
                                                                                                : 1.5 * lv.dx;
    centre[static_cast<std::size_t>(normal)] = xb[normal] - X[normal];
    reach = 1.5 * lv.dx;
  }
  if (reach < 1.5 * lv.dx)
    throw core::RunFailure(fmt::format(
        "multigrid: the Robin centre ({}, {}, {}) is within 1.5 cells of the face point ({}, {}, {}) on level {}",
        centre[0], centre[1], centre[2], xb[0], xb[1], xb[2], lv.index));
  const int planes = two_point || reach < 2.5 * lv.dx ? 1 : 2;
  // Ray weights of u(x_m) - u_inf: s_1 (two-point), or (4 s_1, -s_2) / 3.
  double ray[2];
  const double s1 = 1.0 - lv.dx / reach, s2 = 1.0 - 2.0 * lv.dx / reach;
  if (planes == 1) {
    ray[0] = s1;
    ray[1] = 0;
  } else {
    ray[0] = 4.0 * s1 / 3.0;
    ray[1] = -s2 / 3.0;
  }
  const int own[3] = {i, j, k};
  // The window per axis (shared by both planes): 3 indices containing own and both targets.
  int first[3];
  for (int a = 0; a < 3; ++a) {
    const double t1 = (centre[a] + s1 * X[a] - lv.origin[a]) / lv.dx - own[a];  // |t1| <= 1
    int f = own[a] - 1;
    if (planes == 2 && t1 < -0.5) f = own[a] - 2;
    if (planes == 2 && t1 > 0.5) f = own[a];
    first[a] = std::clamp(f, 0, last[a] - 2);
  }
  for (int m = 0; m < planes; ++m) {
    const double s = m == 0 ? s1 : s2;
    int start[3], count[3];
    double w[3][3];
    // The axis (or axes) with |X_a| = reach is exact: x_m lies on a grid plane. Other axes
    // interpolate with the window's 3 points.
    for (int a = 0; a < 3; ++a) {
      const double t = (centre[a] + s * X[a] - lv.origin[a]) / lv.dx;
      const double nearest = std::round(t);
      if (std::fabs(t - nearest) < 1e-9) {
        start[a] = std::clamp(static_cast<int>(nearest), 0, last[a]);
        count[a] = 1;
        w[a][0] = 1;
        continue;
      }
      start[a] = first[a];
      count[a] = 3;
      const double u = t - first[a];  // nodes at 0, 1, 2
      w[a][0] = 0.5 * (u - 1) * (u - 2);
      w[a][1] = -u * (u - 2);
      w[a][2] = 0.5 * u * (u - 1);
    }
    if (count[0] * count[1] * count[2] > 9)
      throw core::RunFailure(fmt::format("multigrid: the Robin row of face point ({}, {}, {}) on level {} needs "
                                         "interpolation along three axes",
                                         i, j, k, lv.index));
    for (int p = 0; p < count[0]; ++p)
      for (int q = 0; q < count[1]; ++q)
        for (int r = 0; r < count[2]; ++r) {
          const double weight = ray[m] * w[0][p] * w[1][q] * w[2][r];
          if (weight == 0) continue;
          row.index[static_cast<std::size_t>(row.count)] = lv.at(start[0] + p, start[1] + q, start[2] + r);
          row.weight[static_cast<std::size_t>(row.count)] = weight;
          ++row.count;
        }
  }
  row.scale = ray[0] + ray[1];
  return row;
}

}  // namespace

RobinRows robin_stencils(const Level& lv, const std::array<double, 3>& centre, bool two_point, bool coarse) {
  // Two passes over the face points in for_face_points order, the threads on contiguous runs of
  // face rows of about equal point counts: the first sizes each row, the second writes them into
  // arrays allocated once, each page first touched by the thread that fills it. Serial (and grown
  // entry by entry) the two row sets of n = 128 took 47 of the multigrid's 58 ms of set-up on 2
  // threads, most of it in page faults.
  struct FaceRow {
    int j, k;
    bool whole;
  };
  std::vector<FaceRow> face_rows;
  std::vector<std::size_t> points_before{0};
  for_face_rows(lv, [&](int j, int k, bool whole) {
    face_rows.push_back({j, k, whole});
    points_before.push_back(points_before.back() + (whole ? static_cast<std::size_t>(lv.nx) : 2));
  });
  const std::size_t total = points_before.back();
  RobinRows rows;
  rows.point.resize(total);
  rows.scale.resize(total);
  rows.begin.resize(total + 1);
  rows.begin[0] = 0;
  // Calls fn(r, i, j, k) for the face points of this thread's runs of face rows, r the row's number.
  auto for_my_points = [&](auto&& fn) {
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t nt = static_cast<std::size_t>(omp_get_num_threads());
    auto first_row = [&](std::size_t part) {
      return static_cast<std::size_t>(
          std::lower_bound(points_before.begin(), points_before.end() - 1, total * part / nt) - points_before.begin());
    };
    for (std::size_t f = first_row(t), f1 = first_row(t + 1); f < f1; ++f) {
      const FaceRow& fr = face_rows[f];
      std::size_t r = points_before[f];
      for_points_of_face_row(lv, fr.whole, [&](int i) { fn(r++, i, fr.j, fr.k); });
    }
  };
  std::vector<std::exception_ptr> failures(static_cast<std::size_t>(omp_get_max_threads()));
#pragma omp parallel
  {
    try {
      for_my_points([&](std::size_t r, int i, int j, int k) {
        const Row row = row_of(lv, centre, two_point, coarse, i, j, k);
        rows.point[r] = lv.at(i, j, k);
        rows.scale[r] = row.scale;
        rows.begin[r + 1] = static_cast<std::size_t>(row.count);
      });
    } catch (...) {
      failures[static_cast<std::size_t>(omp_get_thread_num())] = std::current_exception();
    }
  }
  // The first failure in for_face_points order, as a serial loop would report (each thread stops at
  // its first).
  for (const std::exception_ptr& f : failures)
    if (f) std::rethrow_exception(f);
  for (std::size_t r = 0; r < total; ++r) rows.begin[r + 1] += rows.begin[r];
  rows.index.resize(rows.begin[total]);
  rows.weight.resize(rows.begin[total]);
#pragma omp parallel
  for_my_points([&](std::size_t r, int i, int j, int k) {
    const Row row = row_of(lv, centre, two_point, coarse, i, j, k);
    const std::size_t e = rows.begin[r];
    for (int n = 0; n < row.count; ++n) {
      rows.index[e + static_cast<std::size_t>(n)] = row.index[static_cast<std::size_t>(n)];
      rows.weight[e + static_cast<std::size_t>(n)] = row.weight[static_cast<std::size_t>(n)];
    }
  });
  return rows;
}

namespace {

/// Up to this many arrays share one pass over the rows (their row sums live in registers).
constexpr std::size_t max_batch = 8;

/// Calls fn(std::integral_constant<int, n>{}) for 1 <= n <= max_batch.
template <class Fn>
void with_batch(std::size_t n, Fn&& fn) {
  switch (n) {
    case 1: return fn(std::integral_constant<int, 1>{});
    case 2: return fn(std::integral_constant<int, 2>{});
    case 3: return fn(std::integral_constant<int, 3>{});
    case 4: return fn(std::integral_constant<int, 4>{});
    case 5: return fn(std::integral_constant<int, 5>{});
    case 6: return fn(std::integral_constant<int, 6>{});
    case 7: return fn(std::integral_constant<int, 7>{});
    default: return fn(std::integral_constant<int, 8>{});
  }
}

/// Inside a parallel region: for every row r (shared among the threads), sum[t] = sum over the
/// row's entries of weight (u_t - u_inf_t), then done(r, sum). Subtracting u_inf per entry (not
/// u_inf times the row's scale afterwards) keeps u = u_inf an exact solution of the rows: a
/// solution that is exact to round-off (P = 0) must have residual 0, not 1e-17 noise that the
/// multigrid's stall test would see. ZeroInf: every u_inf is 0 (the vector potential and the
/// shift, six of the eight arrays), and the subtraction goes: the loop is bound by its
/// floating-point operations, and a third fewer made the six arrays' rows 5-15 % faster
/// (bhnsid-bench robin).
template <int N, bool ZeroInf, class Done>
void row_sums_of(const RobinRows& rows, const std::array<const double*, N>& u, const std::array<double, N>& u_inf,
                 Done&& done) {
  const auto n = static_cast<std::ptrdiff_t>(rows.size());
  const std::size_t* begin = rows.begin.data();
  const std::ptrdiff_t* index = rows.index.data();
  const double* weight = rows.weight.data();
  // Chunks of 256 rows dealt in turn: the rows go plane by plane, and the top face's rows (the
  // last third, cheap: contiguous data) would otherwise all fall to the last thread (2 threads:
  // the residuals 15 % faster).
#pragma omp for schedule(static, 256)
  for (std::ptrdiff_t r = 0; r < n; ++r) {
    std::array<double, N> sum{};
    for (std::size_t e = begin[r]; e < begin[r + 1]; ++e) {
      const double w = weight[e];
      const std::ptrdiff_t i = index[e];
      if constexpr (ZeroInf)
        for (int t = 0; t < N; ++t) sum[t] += w * u[t][i];
      else
        for (int t = 0; t < N; ++t) sum[t] += w * (u[t][i] - u_inf[t]);
    }
    done(static_cast<std::size_t>(r), sum);
  }
}

template <int N, class Done>
void row_sums(const RobinRows& rows, const std::array<const double*, N>& u, const std::array<double, N>& u_inf,
              Done&& done) {
  bool zero = true;
  for (int t = 0; t < N; ++t) zero = zero && u_inf[t] == 0.0;
  if (zero)
    row_sums_of<N, true>(rows, u, u_inf, done);
  else
    row_sums_of<N, false>(rows, u, u_inf, done);
}

/// Splits items (each with .u and .u_inf) into batches of at most max_batch and calls
/// fn(batch, first, u, u_inf) for each: batch an std::integral_constant with the batch's size N,
/// first its first item, u and u_inf the batch's arrays and asymptotic values for row_sums.
template <class Item, class Fn>
void in_batches(const std::vector<Item>& items, Fn&& fn) {
  for (std::size_t start = 0; start < items.size(); start += max_batch)
    with_batch(std::min(max_batch, items.size() - start), [&](auto batch) {
      constexpr int N = decltype(batch)::value;
      const Item* first = items.data() + start;
      std::array<const double*, N> u;
      std::array<double, N> u_inf;
      for (int t = 0; t < N; ++t) u[t] = first[t].u, u_inf[t] = first[t].u_inf;
      fn(batch, first, u, u_inf);
    });
}

}  // namespace

namespace {

/// Every row's residual of every field, rhs - B(u) (rhs nullptr: zero; 0 at held points), handed
/// to store(r, t, p, value) for row r, field t (its index in fields) and the row's point p.
template <class Store>
void row_residuals(const RobinRows& rows, const std::vector<RobinResidual>& fields, Store&& store) {
  // `store` reaches the parallel region as an init-capture: clang 14 cannot capture the enclosing
  // function's parameter itself through the outlined OpenMP region of a generic lambda.
  in_batches(fields, [&, put = &store](auto batch, const RobinResidual* f, const auto& u, const auto& u_inf) {
    constexpr int N = decltype(batch)::value;
    const std::size_t first = static_cast<std::size_t>(f - fields.data());
    auto& store = *put;
#pragma omp parallel if (static_cast<long>(rows.size()) >= stencil::parallel_min_points)
    row_sums<N>(rows, u, u_inf, [&](std::size_t r, const std::array<double, N>& sum) {
      const std::ptrdiff_t p = rows.point[r];
      for (int t = 0; t < N; ++t) {
        const RobinResidual& x = f[t];
        const double b = (x.u[p] - x.u_inf) - sum[t];
        store(r, first + static_cast<std::size_t>(t), p, x.fixed && x.fixed[p] ? 0.0 : (x.rhs ? x.rhs[p] : 0.0) - b);
      }
    });
  });
}

}  // namespace

void robin_residual(const RobinRows& rows, const std::vector<RobinResidual>& fields) {
  row_residuals(rows, fields,
                [&](std::size_t, std::size_t t, std::ptrdiff_t p, double value) { fields[t].res[p] = value; });
}

void robin_residual_rows(const RobinRows& rows, const std::vector<RobinResidual>& fields, double* out) {
  const std::size_t n = fields.size();
  row_residuals(rows, fields,
                [&](std::size_t r, std::size_t t, std::ptrdiff_t, double value) { out[r * n + t] = value; });
}

void robin_relax(const RobinRows& rows, const std::vector<RobinTarget>& targets) {
  in_batches(targets, [&](auto batch, const RobinTarget* x, const auto& u, const auto& u_inf) {
    constexpr int N = decltype(batch)::value;
    rows.next.resize(rows.size() * N);
    double* next = rows.next.data();
#pragma omp parallel if (static_cast<long>(rows.size()) >= stencil::parallel_min_points)
    {
      row_sums<N>(rows, u, u_inf, [&](std::size_t r, const std::array<double, N>& sum) {
        const std::ptrdiff_t p = rows.point[r];
        for (int t = 0; t < N; ++t)
          next[r * N + t] =
              x[t].fixed && x[t].fixed[p] ? x[t].u[p] : x[t].u_inf + sum[t] + (x[t].rhs ? x[t].rhs[p] : 0.0);
      });
      const auto n = static_cast<std::ptrdiff_t>(rows.size());
#pragma omp for schedule(static, 256)  // as row_sums: the x faces' rows are the costly ones
      for (std::ptrdiff_t r = 0; r < n; ++r)
        for (int t = 0; t < N; ++t)
          x[t].u[rows.point[static_cast<std::size_t>(r)]] = next[static_cast<std::size_t>(r) * N + t];
    }
  });
}

void zero_faces(const Level& lv, double* res) {
  for_face_points(lv, [&](int i, int j, int k) { res[lv.at(i, j, k)] = 0.0; });
}

}  // namespace bhnsid::multigrid
