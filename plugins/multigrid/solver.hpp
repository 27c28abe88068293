#pragma once
// The FAS multigrid solver for every registered EllipticEquation at once: FMG start, V, W or F
// cycles of red-black nonlinear Gauss-Seidel, full-weighting restriction of residuals and
// coefficients, injection of the solution, trilinear prolongation of corrections, a direct Newton
// solve on the coarsest level, and a monitor that stops at a fraction of the truncation error.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/core/checkpoint.hpp"
#include "bhnsid/core/log.hpp"
#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "boundary_rows.hpp"

namespace bhnsid::multigrid {

/// The coarsest level's direct solve is bounded to this many unknowns (its LU fill and time, docs/reliability.md).
inline constexpr double max_coarse_rows = 60000;

enum class CycleType { v, w, f };

struct Settings {
  CycleType cycle = CycleType::v;
  int pre_sweeps = 2, post_sweeps = 2;
  double omega = 1.15;           ///< over-relaxation of the point Newton steps
  bool fmg = true;
  int fmg_cycles = 1;
  bool warm_start = true;        ///< after a converged solve, the next starts from its fields (no FMG)
  double fmg_restart = 0;        ///< > 0: ... unless its residual exceeds this times tau: then FMG
  double tau_factor = 1e-3;      ///< converged when |r| <= tau_factor |tau| for every equation
  double abs_tolerance = 0;      ///< ... or |r| <= abs_tolerance (0: off)
  int max_cycles = 30;
  double stall_factor = 0.95;    ///< a cycle reducing |r| by less than this counts as stalled
  int stall_cycles = 3;          ///< that many stalled cycles in a row end the solve
  double divergence_factor = 1e4;
  int min_cycles = 1;            ///< cycles from the finest level after the FMG start
};

/// One finest-level cycle: rms residual and truncation-error estimate per equation.
struct CycleRecord {
  int cycle = 0;  ///< 0: the state after the FMG start
  std::vector<double> residual, tau;
  double factor = 0;  ///< worst equation's residual reduction in this cycle
  double seconds = 0;
};

struct SolveReport {
  bool converged = false;
  int cycles = 0;
  std::vector<std::string> equations;
  std::vector<CycleRecord> history;
  double mean_factor = 0;  ///< geometric mean of the per-cycle factors
  double seconds = 0;      ///< the whole solve, FMG start included
  /// Mean wall time of one full red-black sweep (both colours, every equation, boundary rows) on the
  /// finest level: what the benchmark turns into memory bandwidth.
  double fine_sweep_seconds = 0;
  int fine_sweeps = 0;
  bool fmg_start = false;  ///< the solve began with FMG (else from the last converged solution)
  std::string message;
};

/// Per equation: its service, fields and boundary rows.
struct Slot {
  EllipticEquation* eq = nullptr;
  std::string name;
  int u = -1, rhs = -1, old = -1;
  int res = -1;  ///< coarse levels only (the finest level's: FasSolver::res) unless the grid has one level
  int ncomp = 1;
  std::vector<Parity> parity;
  OuterBoundary boundary;
  int rows = -1;                                // index into FasSolver::row_sets_; -1 for Dirichlet
  int face_column = 0;                          // its first component's column in boundary_residuals' output
  int mask = -1;
  std::vector<int> coefficients;
};

class CoarseSolver;

class FasSolver {
 public:
  FasSolver(Grid& grid, const std::vector<EllipticEquation*>& equations, Settings settings, core::Log log);
  ~FasSolver();

  /// Solves to the stopping criterion; throws core::StepFailure on NaN, divergence, stagnation or
  /// max_cycles (a smaller outer step may cure them), core::RunFailure on a broken setup, naming the equation and, for NaN, the point, followed by every equation's
  /// failure_hint().
  /// cycle_cap > 0: stop unconverged (not failed) after that many cycles, keeping the fields for
  /// the next solve to continue (an outer iteration whose sources still move).
  SolveReport solve(int cycle_cap = 0);
  const std::vector<Slot>& slots() const { return slots_; }
  /// The levels the cycle uses: the grid's, cut above the first level too coarse for a Robin centre.
  int levels() const { return levels_; }
  /// Copies the finest level's unknowns (and whether they are a converged solution), so that a
  /// failed solve can be undone.
  void keep_start();
  /// Puts back what keep_start() copied; false when nothing was kept.
  bool restore_start();
  /// What the next solve starts from beyond the fields (solver_checkpoint.cpp): whether they are
  /// warm, the truncation-error estimates, the coarsest level's chord Jacobian.
  void save(core::CheckpointWriter& out) const;
  void restore(const core::CheckpointReader& in);
  /// From the next coarser run (bhnsid run --warm-start): whether its fields, which the grid
  /// interpolates, are warm, and its truncation-error estimates (about 4x this lattice's: the FMG
  /// restart and divergence thresholds of the first solve err high). The coarsest level's Jacobian
  /// is this run's own: it goes with the masks, which are this run's.
  void warm_start_from_coarser(const core::CheckpointReader& in);
  /// The history of the last solve, also after it failed.
  const SolveReport& last_report() const { return report_; }

 private:
  SolveReport solve_cycles(int cycle_cap);
  friend class CoarseSolver;
  void prepare();
  void cycle(int l, CycleType type);
  void smooth(int l, int sweeps);
  /// res = rhs - L(u) of one equation on level l (interior and boundary rows; 0 where held), its
  /// ghosts filled. rows_done: the boundary rows' part comes from the last boundary_residuals(l).
  void residual_of(const Slot& s, int l, bool rows_done = false);
  /// The boundary rows' residuals of every equation on level l, one pass per row set (the
  /// equations about one centre together), for residual_of(s, l, true) to hand out: u must not
  /// change in between.
  void boundary_residuals(int l);
  /// The boundary rows' residual targets of s's components on level l (res from out, or none).
  std::vector<RobinResidual> boundary_targets(const Slot& s, int l, const std::vector<double*>& out) const;
  /// residual_of every equation on level l (not on the finest level of several, whose residuals
  /// share one array set).
  void residual(int l);
  /// The residual array of component c of s on level l.
  double* res(const Slot& s, int c, int l);
  /// From level l to l+1: u and old by injection, then per equation its residual and rhs = L(u) +
  /// FW(res). When l = 0 the truncation-error norms are taken from the new rhs.
  void descend(int l);
  /// u_l += P(u_{l+1} - old_{l+1}); cubic P for the FMG step, trilinear in cycles.
  void correct(int l, bool cubic);
  /// The ghosts of every unknown on level l (equatorial symmetry).
  void fill_ghosts(int l);
  double rms_interior(const Slot& s, const std::vector<const double*>& field, int l) const;
  /// The same over the interior points of `lv`, a part of level l (covered_part).
  double rms_interior(const Slot& s, const std::vector<const double*>& field, const Level& lv, int l) const;
  /// Over the points where level l solves its own equation: with nested boxes, its interior less
  /// the part the finer box covers.
  double rms_own(const Slot& s, const std::vector<const double*>& field, int l) const;
  /// Sum of squares and count of points of rms_interior, on this process.
  std::array<double, 2> squares_interior(const Slot& s, const std::vector<const double*>& field, const Level& lv,
                                         int l) const;
  [[noreturn]] void fail_nonfinite(int cycle_number);
  RelaxArgs args(const Slot& s, int l) const;

  Grid& grid_;
  Settings settings_;
  core::Log log_;
  int levels_ = 0;
  int boxes_ = 1;  ///< nested boxes: levels 0 .. boxes_ - 1 (Grid::num_boxes)
  std::vector<Slot> slots_;
  // Robin rows per distinct falloff centre, per level: equations about one centre share them, and
  // the smoother relaxes all their components in one pass over the rows.
  std::vector<std::vector<RobinRows>> row_sets_;
  std::vector<std::array<double, 3>> row_centres_;
  // Per row set, boundary_residuals' output: [row][column], the set's equations' components side by side.
  std::vector<std::vector<double>> face_residuals_;
  const RobinRows& rows(const Slot& s, int level) const {
    return row_sets_[static_cast<std::size_t>(s.rows)][static_cast<std::size_t>(level)];
  }
  std::vector<char> rhs_zero_;  // per level: the right-hand side is identically zero
  std::vector<double> tau_;     // per equation, from the last descent from the finest level
  int fine_residual_ = -1;      // the finest level's residual, shared by the equations; -1: one level
  std::unique_ptr<CoarseSolver> coarse_;
  SolveReport report_;
  bool warm_ = false;  ///< the fields hold the last converged solve's solution
  std::vector<double> start_;  ///< keep_start(): every unknown component of the finest level
  bool start_warm_ = false, has_start_ = false;
  // Pointer tables handed to the equations: [slot][level][component].
  std::vector<std::vector<std::vector<const double*>>> rhs_ptrs_;
};

}  // namespace bhnsid::multigrid
