#pragma once
// The coarsest level solved directly: Newton's method on all equations at once, with the Jacobian
// of the discrete residual built by finite-difference probing (125 colours: a row depends only on
// points within 2 of its own per axis, a window of 5 with one point per residue class mod 5, so
// each changed row names the probed column) and factorised by
// Eigen's SparseLU. The factorisation is kept and reused (a chord iteration) while it still
// converges fast; the problem is tiny, so every solve ends at round-off.
#include <Eigen/SparseLU>

#include "bhnsid/core/checkpoint.hpp"
#include <cstddef>
#include <vector>

namespace bhnsid::multigrid {

class FasSolver;

class CoarseSolver {
 public:
  explicit CoarseSolver(FasSolver& solver) : solver_(solver) {}
  /// Indexes the unknowns again at the next solve: the held points (excision masks) may change
  /// between solves, e.g. when the black hole moves. The factorisation is kept when they did not
  /// (an outer iteration's next solve): it is a chord Jacobian, rebuilt when it stops converging.
  void reset() { level_ = -1; }
  void solve(int level);
  /// The index of the unknowns and the Jacobian the chord iteration reuses; restore factorises it
  /// again (SparseLU of the same matrix gives the same factors, so the next solve is unchanged).
  void save(core::CheckpointWriter& out) const;
  void restore(const core::CheckpointReader& in);

 private:
  struct Unknown {
    int slot, comp;
    std::ptrdiff_t point;
    int i, j, k;
    bool operator==(const Unknown& o) const { return slot == o.slot && comp == o.comp && point == o.point; }
  };
  void index_unknowns(int level);
  void residual_vector(int level, Eigen::VectorXd& out);
  void factorise(int level, const Eigen::VectorXd& r0);
  double* value(const Unknown& x, int level, bool residual);
  /// jacobian_ from its entries, factorised into lu_; false when singular.
  bool factorise_entries(Eigen::Index n, const std::vector<Eigen::Triplet<double>>& entries);

  FasSolver& solver_;
  int level_ = -1;
  int factorised_level_ = -1;  // the level lu_ belongs to
  std::vector<Unknown> unknowns_;
  std::vector<std::ptrdiff_t> row_of_;  // per (slot, comp, point) -> row, -1 if held
  std::vector<std::size_t> slot_offset_;
  Eigen::SparseMatrix<double> jacobian_;  // what lu_ factorised, kept for a checkpoint
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
  bool factorised_ = false;
};

}  // namespace bhnsid::multigrid
