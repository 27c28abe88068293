// The solver's measures of a solution: the rms residual over the points it relaxes, and the report
// of the first non-finite value (equation, component, point) when a solve blows up.
#include <fmt/format.h>

#include <array>
#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/interfaces/stencil.hpp"
#include "solver.hpp"

namespace bhnsid::multigrid {


double FasSolver::rms_interior(const Slot& s, const std::vector<const double*>& field, int l) const {
  return rms_interior(s, field, grid_.level(l), l);
}

double FasSolver::rms_own(const Slot& s, const std::vector<const double*>& field, int l) const {
  if (l == 0 || !grid_.level(l - 1).inner) return rms_interior(s, field, l);
  // Nested boxes: level l's own points are its interior less the interior of the part the finer
  // box covers (there level l solves the finer box's FAS equation, not its own).
  const auto [sum, count] = squares_interior(s, field, grid_.level(l), l);
  const auto [part_sum, part_count] = squares_interior(s, field, covered_part(grid_.level(l), grid_.level(l - 1)), l);
  const double own = grid_.global_sum(sum - part_sum), points = grid_.global_sum(count - part_count);
  return points > 0 ? std::sqrt(std::fmax(own, 0.0) / points) : 0.0;
}

double FasSolver::rms_interior(const Slot& s, const std::vector<const double*>& field, const Level& lv, int l) const {
  const auto [sum, count] = squares_interior(s, field, lv, l);
  const double total = grid_.global_sum(sum), points = grid_.global_sum(count);
  return points > 0 ? std::sqrt(total / points) : 0.0;
}

std::array<double, 2> FasSolver::squares_interior(const Slot& s, const std::vector<const double*>& field,
                                                  const Level& lv, int l) const {
  const std::uint8_t* fixed = s.mask >= 0 ? grid_.mask(s.mask, l) : nullptr;
  const int end = lv.nx - 1;
  double sum = 0, count = 0;
  for (int c = 0; c < s.ncomp; ++c) {
    const double* v = field[static_cast<std::size_t>(c)];
#pragma omp parallel for reduction(+ : sum, count) schedule(static) if (stencil::interior_points(lv) >= stencil::parallel_min_points)
    for (int k = lv.k_begin(); k < lv.nz - 1; ++k)
      for (int j = 1; j < lv.ny - 1; ++j) {
        const double* row = v + lv.at(0, j, k);
        // Held points lie in a few rows only (an excision cube): the others take the plain loop.
        if (!fixed || !stencil::row_has_fixed(fixed + lv.at(0, j, k), end)) {
          double line = 0;
#pragma omp simd reduction(+ : line)
          for (int i = 1; i < end; ++i) line += row[i] * row[i];
          sum += line;
          count += end - 1;
          continue;
        }
        // Held points selected away, not branched over: the loop vectorises.
        const std::uint8_t* held = fixed + lv.at(0, j, k);
        double line = 0, points = 0;
#pragma omp simd reduction(+ : line, points)
        for (int i = 1; i < end; ++i) {
          const double v = held[i] ? 0.0 : row[i];
          line += v * v;
          points += held[i] ? 0.0 : 1.0;
        }
        sum += line;
        count += points;
      }
  }
  return {sum, count};
}

void FasSolver::fail_nonfinite(int cycle_number) {
  const Level& lv = grid_.finest();
  // The first non-finite value, or else (a norm that overflowed) the largest one, with its place.
  const Slot* where_slot = nullptr;
  int where_field = -1, where_comp = 0, wi = 0, wj = 0, wk = 0;
  double largest = -1;
  for (const Slot& s : slots_)
    for (int which : {s.u, s.res}) {
      if (which == s.res) residual_of(s, 0);  // the finest level's residuals share one array set
      for (int c = 0; c < s.ncomp; ++c) {
        const double* v = which == s.u ? grid_.data(s.u, c, 0) : res(s, c, 0);
        for (int k = 0; k < lv.nz; ++k)
          for (int j = 0; j < lv.ny; ++j)
            for (int i = 0; i < lv.nx; ++i) {
              const double x = v[lv.at(i, j, k)];
              if (!std::isfinite(x))
                throw core::StepFailure(fmt::format(
                    "multigrid: {} of equation '{}' (component {}) is {} at point ({}, {}, {}) = ({:.6g}, {:.6g}, "
                    "{:.6g}) after {}",
                    which == s.u ? "the solution" : "the residual", s.name, c, x, i, j, k, lv.x(i), lv.y(j), lv.z(k),
                    cycle_number == 0 ? "the FMG start" : fmt::format("cycle {}", cycle_number)));
              if (std::fabs(x) > largest) {
                largest = std::fabs(x);
                where_slot = &s;
                where_field = which;
                where_comp = c;
                wi = i, wj = j, wk = k;
              }
            }
      }
    }
  throw core::StepFailure(fmt::format(
      "multigrid: the residual norm overflows after {}: the largest value is {} = {:.3e} of equation '{}' "
      "(component {}) at point ({}, {}, {}) = ({:.6g}, {:.6g}, {:.6g})",
      cycle_number == 0 ? "the FMG start" : fmt::format("cycle {}", cycle_number),
      where_slot && where_field == where_slot->u ? "the solution" : "the residual", largest,
      where_slot ? where_slot->name : "?", where_comp, wi, wj, wk, lv.x(wi), lv.y(wj), lv.z(wk)));
}

}  // namespace bhnsid::multigrid
