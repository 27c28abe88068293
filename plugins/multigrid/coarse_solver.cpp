#include "coarse_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "solver.hpp"

namespace bhnsid::multigrid {

double* CoarseSolver::value(const Unknown& x, int level, bool residual) {
  const Slot& s = solver_.slots_[static_cast<std::size_t>(x.slot)];
  return (residual ? solver_.res(s, x.comp, level) : solver_.grid_.data(s.u, x.comp, level)) + x.point;
}

void CoarseSolver::index_unknowns(int level) {
  const Level& lv = solver_.grid_.level(level);
  const std::vector<Unknown> previous = std::move(unknowns_);
  unknowns_.clear();
  slot_offset_.clear();
  std::size_t offset = 0;
  for (std::size_t si = 0; si < solver_.slots_.size(); ++si) {
    const Slot& s = solver_.slots_[si];
    const std::uint8_t* fixed = s.mask >= 0 ? solver_.grid_.mask(s.mask, level) : nullptr;
    slot_offset_.push_back(offset);
    offset += static_cast<std::size_t>(s.ncomp) * lv.size;
    for (int c = 0; c < s.ncomp; ++c)
      for (int k = 0; k < lv.nz; ++k)
        for (int j = 0; j < lv.ny; ++j)
          for (int i = 0; i < lv.nx; ++i) {
            const std::ptrdiff_t p = lv.at(i, j, k);
            if (fixed && fixed[p]) continue;
            if (lv.on_outer_face(i, j, k) && s.rows < 0) continue;  // Dirichlet rows
            unknowns_.push_back(Unknown{static_cast<int>(si), c, p, i, j, k});
          }
  }
  row_of_.assign(offset, -1);
  for (std::size_t r = 0; r < unknowns_.size(); ++r) {
    const Unknown& x = unknowns_[r];
    row_of_[slot_offset_[static_cast<std::size_t>(x.slot)] + static_cast<std::size_t>(x.comp) * lv.size +
            static_cast<std::size_t>(x.point)] = static_cast<std::ptrdiff_t>(r);
  }
  level_ = level;
  factorised_ = factorised_ && level == factorised_level_ && unknowns_ == previous;
}

void CoarseSolver::save(core::CheckpointWriter& out) const {
  out.put_integers("coarse/state", {level_, factorised_level_, factorised_ ? 1 : 0});
  std::vector<std::int64_t> unknowns;
  for (const Unknown& x : unknowns_)
    for (std::int64_t v : {std::int64_t{x.slot}, std::int64_t{x.comp}, std::int64_t{x.point}, std::int64_t{x.i},
                           std::int64_t{x.j}, std::int64_t{x.k}})
      unknowns.push_back(v);
  out.put_integers("coarse/unknowns", unknowns);
  out.put_integers("coarse/row_of", std::vector<std::int64_t>(row_of_.begin(), row_of_.end()));
  out.put_integers("coarse/slot_offset", std::vector<std::int64_t>(slot_offset_.begin(), slot_offset_.end()));
  if (!factorised_) return;
  const auto nnz = static_cast<std::size_t>(jacobian_.nonZeros());
  out.put_integers("coarse/jacobian_size", {jacobian_.rows()});
  out.put_integers("coarse/jacobian_outer",
                   std::vector<std::int64_t>(jacobian_.outerIndexPtr(), jacobian_.outerIndexPtr() + jacobian_.outerSize() + 1));
  out.put_integers("coarse/jacobian_inner", std::vector<std::int64_t>(jacobian_.innerIndexPtr(), jacobian_.innerIndexPtr() + nnz));
  out.put("coarse/jacobian_values", jacobian_.valuePtr(), nnz);
}

void CoarseSolver::restore(const core::CheckpointReader& in) {
  const std::vector<std::int64_t> state = in.integers("coarse/state");
  const std::vector<std::int64_t> unknowns = in.integers("coarse/unknowns");
  if (state.size() != 3 || unknowns.size() % 6 != 0)
    throw core::InputError("multigrid: the checkpoint's coarsest-level state is malformed");
  level_ = static_cast<int>(state[0]);
  factorised_level_ = static_cast<int>(state[1]);
  factorised_ = state[2] != 0;
  unknowns_.clear();
  for (std::size_t u = 0; u < unknowns.size(); u += 6)
    unknowns_.push_back(Unknown{static_cast<int>(unknowns[u]), static_cast<int>(unknowns[u + 1]),
                                static_cast<std::ptrdiff_t>(unknowns[u + 2]), static_cast<int>(unknowns[u + 3]),
                                static_cast<int>(unknowns[u + 4]), static_cast<int>(unknowns[u + 5])});
  const std::vector<std::int64_t> rows = in.integers("coarse/row_of"), offsets = in.integers("coarse/slot_offset");
  row_of_.assign(rows.begin(), rows.end());
  slot_offset_.assign(offsets.begin(), offsets.end());
  if (!factorised_) return;
  const auto n = static_cast<Eigen::Index>(in.integers("coarse/jacobian_size").at(0));
  const std::vector<std::int64_t> outer = in.integers("coarse/jacobian_outer"), inner = in.integers("coarse/jacobian_inner");
  const std::vector<double> values = in.reals("coarse/jacobian_values");
  if (static_cast<Eigen::Index>(outer.size()) != n + 1 || inner.size() != values.size() ||
      static_cast<std::size_t>(outer.back()) != values.size())
    throw core::InputError("multigrid: the checkpoint's coarsest-level Jacobian is malformed");
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index c = 0; c < n; ++c)
    for (std::int64_t e = outer[static_cast<std::size_t>(c)]; e < outer[static_cast<std::size_t>(c) + 1]; ++e)
      entries.emplace_back(static_cast<int>(inner[static_cast<std::size_t>(e)]), static_cast<int>(c),
                           values[static_cast<std::size_t>(e)]);
  if (!factorise_entries(n, entries))
    throw core::RunFailure("multigrid: the checkpoint's coarsest-level Jacobian does not factorise again");
}

bool CoarseSolver::factorise_entries(Eigen::Index n, const std::vector<Eigen::Triplet<double>>& entries) {
  jacobian_ = Eigen::SparseMatrix<double>(n, n);
  jacobian_.setFromTriplets(entries.begin(), entries.end());
  jacobian_.makeCompressed();
  lu_.analyzePattern(jacobian_);
  lu_.factorize(jacobian_);
  return lu_.info() == Eigen::Success;
}

void CoarseSolver::residual_vector(int level, Eigen::VectorXd& out) {
  solver_.residual(level);
  out.resize(static_cast<Eigen::Index>(unknowns_.size()));
  for (std::size_t r = 0; r < unknowns_.size(); ++r) out[static_cast<Eigen::Index>(r)] = *value(unknowns_[r], level, true);
}

void CoarseSolver::factorise(int level, const Eigen::VectorXd& r0) {
  const Level& lv = solver_.grid_.level(level);
  const int last[3] = {lv.nx - 1, lv.ny - 1, lv.nz - 1};
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd r1;
  std::vector<double> step(unknowns_.size());
  // Every row depends only on indices within 2 of its own per axis (interior: +-1; Robin rows: the
  // inward points 0..2 along the normal and a 3-point window about their own index, shifted by one
  // toward the centre where the ray's targets are more than half a cell off, along the faces;
  // boundary_rows.hpp), all inside the window of 5 starting at index - 2, clamped to the level:
  // exactly one point of each residue class mod 5 lies in it, which identifies the column a
  // changed row belongs to.
  auto window_start = [&](int index, int axis) { return std::max(0, std::min(index - 2, last[axis] - 4)); };
  for (std::size_t si = 0; si < solver_.slots_.size(); ++si) {
    const Slot& s = solver_.slots_[si];
    for (int c = 0; c < s.ncomp; ++c)
      for (int colour = 0; colour < 125; ++colour) {
        const int ci = colour % 5, cj = (colour / 5) % 5, ck = colour / 25;
        bool any = false;
        for (std::size_t r = 0; r < unknowns_.size(); ++r) {
          const Unknown& x = unknowns_[r];
          if (x.slot != static_cast<int>(si) || x.comp != c || x.i % 5 != ci || x.j % 5 != cj || x.k % 5 != ck) continue;
          double* u = value(x, level, false);
          step[r] = 1e-7 * std::max(1.0, std::fabs(*u));
          *u += step[r];
          any = true;
        }
        if (!any) continue;
        solver_.fill_ghosts(level);
        residual_vector(level, r1);
        for (std::size_t r = 0; r < unknowns_.size(); ++r) {
          const double d = r1[static_cast<Eigen::Index>(r)] - r0[static_cast<Eigen::Index>(r)];
          if (d == 0) continue;
          const Unknown& row = unknowns_[r];
          const int idx[3] = {row.i, row.j, row.k};
          const int want[3] = {ci, cj, ck};
          int col_index[3];
          for (int a = 0; a < 3; ++a) {
            int v = window_start(idx[a], a);
            while (v % 5 != want[a]) ++v;
            col_index[a] = v;
          }
          if (col_index[2] < 0 || col_index[2] > last[2] || col_index[0] > last[0] || col_index[1] > last[1]) continue;
          const std::size_t key = slot_offset_[si] + static_cast<std::size_t>(c) * lv.size +
                                  static_cast<std::size_t>(lv.at(col_index[0], col_index[1], col_index[2]));
          const std::ptrdiff_t col = row_of_[key];
          if (col < 0) continue;  // a held value: no unknown there
          entries.emplace_back(static_cast<int>(r), static_cast<int>(col), d / step[static_cast<std::size_t>(col)]);
        }
        for (std::size_t r = 0; r < unknowns_.size(); ++r) {
          const Unknown& x = unknowns_[r];
          if (x.slot != static_cast<int>(si) || x.comp != c || x.i % 5 != ci || x.j % 5 != cj || x.k % 5 != ck) continue;
          *value(x, level, false) -= step[r];
        }
        solver_.fill_ghosts(level);
      }
  }
  const auto n = static_cast<Eigen::Index>(unknowns_.size());
  if (!factorise_entries(n, entries))
    throw core::RunFailure(fmt::format("multigrid: the coarsest level's Jacobian ({} unknowns) is singular: {}",
                                       unknowns_.size(), lu_.lastErrorMessage()));
  factorised_ = true;
  factorised_level_ = level;
}

void CoarseSolver::solve(int level) {
  if (level != level_) index_unknowns(level);
  solver_.fill_ghosts(level);
  Eigen::VectorXd r;
  residual_vector(level, r);
  double norm = r.lpNorm<Eigen::Infinity>();
  // Round-off floor of a residual made of differences of u over h^2.
  double umax = 0;
  for (const Unknown& x : unknowns_) umax = std::max(umax, std::fabs(*value(x, level, false)));
  const double h = solver_.grid_.level(level).dx;
  const double floor = 1e-13 * umax / (h * h) + 1e-14 * norm;
  for (int iteration = 0; iteration < 20 && norm > floor; ++iteration) {
    const bool fresh = !factorised_;
    if (fresh) factorise(level, r);
    // The residual is rhs - L(u), so J_r = -dL/du and the Newton step solves J_r du = -r.
    const Eigen::VectorXd du = lu_.solve(-r);
    for (std::size_t k = 0; k < unknowns_.size(); ++k) *value(unknowns_[k], level, false) += du[static_cast<Eigen::Index>(k)];
    solver_.fill_ghosts(level);
    residual_vector(level, r);
    const double next = r.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(next)) {
      // Measured: a compact star's matter term turns a 5 x 5 x 3 coarsest level indefinite
      // (docs/performance.md, mu_bn = 10), where a finer coarsest level converges.
      const Level& lv = solver_.grid_.level(level);
      throw core::StepFailure(fmt::format(
          "multigrid: the coarsest-level Newton solve produced a non-finite residual (level {}: {} x {} x {} points, "
          "dx = {}); a level this coarse may not represent the equations: grid.min_coarse_intervals (or "
          "grid.max_levels) keeps the coarsest level finer",
          level, lv.nx, lv.ny, lv.nz, lv.dx));
    }
    const double ratio = next / norm;
    norm = next;
    if (ratio > 0.5) {
      if (fresh) break;     // a fresh Jacobian that gains nothing: nothing left above round-off
      factorised_ = false;  // a stale one: rebuild at the current state
    }
  }
}

}  // namespace bhnsid::multigrid
