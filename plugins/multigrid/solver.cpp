#include "solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <cmath>
#include <optional>
#include <set>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/interrupt.hpp"
#include "bhnsid/interfaces/stencil.hpp"
#include "coarse_solver.hpp"
#include "transfer.hpp"

namespace bhnsid::multigrid {

using core::RunFailure;

FasSolver::FasSolver(Grid& grid, const std::vector<EllipticEquation*>& equations, Settings settings, core::Log log)
    : grid_(grid), settings_(settings), log_(std::move(log)) {
  if (equations.empty()) throw RunFailure("multigrid: no elliptic equation is registered (no equation.* service)");
  levels_ = grid.num_levels();
  boxes_ = grid.num_boxes();
  // The finest level's residual is formed, normed and restricted one equation at a time in one
  // shared array set (a single level keeps one per equation: its direct solve needs them all).
  const bool shared_fine_residual = levels_ > 1;
  int most_components = 1;
  std::set<std::string> unknowns_seen;
  for (EllipticEquation* eq : equations) {
    Slot s;
    s.eq = eq;
    s.name = eq->name();
    const std::string unknown = eq->unknown();
    if (!unknowns_seen.insert(unknown).second)
      throw RunFailure(fmt::format("multigrid: two equations solve for the same field '{}'", unknown));
    s.u = grid.field_id(unknown);
    const FieldInfo info = grid.field_info(s.u);  // a copy: add_field below may move the original
    if (info.storage != core::Storage::all_levels)
      throw RunFailure(fmt::format("multigrid: the unknown '{}' of equation '{}' must be stored on all levels", unknown,
                                   s.name));
    s.ncomp = static_cast<int>(info.components.size());
    s.parity = info.parity;
    const core::TimeParity tp = info.parity[0].y == core::reflection_parity(info.components[0], 1)
                                    ? core::TimeParity::even
                                    : core::TimeParity::odd;
    // The finest level's right-hand side is zero and its start is never saved.
    s.rhs = grid.add_field("multigrid." + unknown + ".rhs", info.components, tp, core::Storage::coarse_levels);
    s.res = grid.add_field("multigrid." + unknown + ".res", info.components, tp,
                           shared_fine_residual ? core::Storage::coarse_levels : core::Storage::all_levels);
    most_components = std::max(most_components, s.ncomp);
    s.old = grid.add_field("multigrid." + unknown + ".old", info.components, tp, core::Storage::coarse_levels);
    s.boundary = eq->boundary();
    if (s.boundary.kind == OuterBoundary::Kind::robin) {
      if (s.boundary.u_inf.size() != static_cast<std::size_t>(s.ncomp))
        throw RunFailure(fmt::format("multigrid: equation '{}' gives {} asymptotic values for {} components", s.name,
                                     s.boundary.u_inf.size(), s.ncomp));
      const auto known = std::find(row_centres_.begin(), row_centres_.end(), s.boundary.centre);
      s.rows = static_cast<int>(known - row_centres_.begin());
      if (known == row_centres_.end()) {
        row_centres_.push_back(s.boundary.centre);
        row_sets_.emplace_back();
        // An inner box's faces take the coarser box's values: no rows there.
        for (int l = 0; l < levels_; ++l)
          row_sets_.back().push_back(grid.level(l).inner ? RobinRows{}
                                                         : robin_stencils(grid.level(l), s.boundary.centre, false,
                                                                          l >= grid.num_boxes()));
      }
    }
    if (s.rows >= 0)
      for (const Slot& other : slots_)
        if (other.rows == s.rows) s.face_column += other.ncomp;
    if (const std::string mask = eq->excision_mask(); !mask.empty()) s.mask = grid.mask_id(mask);
    for (const std::string& name : eq->coefficients()) s.coefficients.push_back(grid.field_id(name));
    slots_.push_back(std::move(s));
  }
  if (shared_fine_residual)
    fine_residual_ = grid.add_field("multigrid.fine_residual",
                                    std::vector<core::TensorKind>(static_cast<std::size_t>(most_components),
                                                                  core::TensorKind::scalar),
                                    core::TimeParity::even, core::Storage::finest_only);
  const int levels = levels_;
  rhs_zero_.assign(static_cast<std::size_t>(levels), 1);
  tau_.assign(slots_.size(), 0.0);
  rhs_ptrs_.resize(slots_.size());
  for (std::size_t s = 0; s < slots_.size(); ++s) {
    rhs_ptrs_[s].resize(static_cast<std::size_t>(levels));
    for (int l = 1; l < levels; ++l)
      for (int c = 0; c < slots_[s].ncomp; ++c) rhs_ptrs_[s][static_cast<std::size_t>(l)].push_back(grid.data(slots_[s].rhs, c, l));
  }
  coarse_ = std::make_unique<CoarseSolver>(*this);
}

FasSolver::~FasSolver() = default;

RelaxArgs FasSolver::args(const Slot& s, int l) const {
  const std::size_t index = static_cast<std::size_t>(&s - slots_.data());
  RelaxArgs a;
  a.level = l;
  a.rhs = rhs_zero_[static_cast<std::size_t>(l)] ? nullptr : rhs_ptrs_[index][static_cast<std::size_t>(l)].data();
  a.fixed = s.mask >= 0 ? grid_.mask(s.mask, l) : nullptr;
  a.omega = settings_.omega;
  return a;
}

void FasSolver::fill_ghosts(int l) {
  if (!grid_.level(l).z_symmetry) return;
  for (const Slot& s : slots_) grid_.fill_ghosts(s.u, l);
}

double* FasSolver::res(const Slot& s, int c, int l) {
  return l == 0 && fine_residual_ >= 0 ? grid_.data(fine_residual_, c, 0) : grid_.data(s.res, c, l);
}

void FasSolver::smooth(int l, int sweeps) {
  const Level& lv = grid_.level(l);
  const auto start = std::chrono::steady_clock::now();
  auto boundary_rows = [&] {
    for (std::size_t set = 0; set < row_sets_.size(); ++set) {
      std::vector<RobinTarget> targets;
      for (const Slot& s : slots_) {
        if (s.rows != static_cast<int>(set)) continue;
        const RelaxArgs a = args(s, l);
        for (int c = 0; c < s.ncomp; ++c)
          targets.push_back(RobinTarget{grid_.data(s.u, c, l), s.boundary.u_inf[static_cast<std::size_t>(c)],
                                        a.rhs ? a.rhs[c] : nullptr, a.fixed});
      }
      robin_relax(row_sets_[set][static_cast<std::size_t>(l)], targets);
    }
    if (!row_sets_.empty()) fill_ghosts(l);
  };
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (const Slot& s : slots_) {
      s.eq->relax(args(s, l));
      if (lv.z_symmetry) grid_.fill_ghosts(s.u, l);
    }
    boundary_rows();
  }
  if (l == 0 && sweeps > 0) {
    report_.fine_sweep_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_.fine_sweeps += sweeps;
  }
}

std::vector<RobinResidual> FasSolver::boundary_targets(const Slot& s, int l, const std::vector<double*>& out) const {
  const RelaxArgs a = args(s, l);
  std::vector<RobinResidual> targets;
  for (int c = 0; c < s.ncomp; ++c)
    targets.push_back(RobinResidual{grid_.data(s.u, c, l), s.boundary.u_inf[static_cast<std::size_t>(c)],
                                    a.rhs ? a.rhs[c] : nullptr, a.fixed,
                                    out.empty() ? nullptr : out[static_cast<std::size_t>(c)]});
  return targets;
}

void FasSolver::boundary_residuals(int l) {
  face_residuals_.resize(row_sets_.size());
  for (std::size_t set = 0; set < row_sets_.size(); ++set) {
    std::vector<RobinResidual> fields;
    for (const Slot& s : slots_)
      if (s.rows == static_cast<int>(set))
        for (const RobinResidual& t : boundary_targets(s, l, {})) fields.push_back(t);
    const RobinRows& r = row_sets_[set][static_cast<std::size_t>(l)];
    face_residuals_[set].resize(r.size() * fields.size());
    robin_residual_rows(r, fields, face_residuals_[set].data());
  }
}

void FasSolver::residual_of(const Slot& s, int l, bool rows_done) {
  const Level& lv = grid_.level(l);
  std::vector<double*> out;
  for (int c = 0; c < s.ncomp; ++c) out.push_back(res(s, c, l));
  s.eq->residual(args(s, l), out.data());
  if (s.rows < 0 || lv.inner) {
    for (double* r : out) zero_faces(lv, r);
  } else if (!rows_done) {
    robin_residual(rows(s, l), boundary_targets(s, l, out));
  } else {
    // From boundary_residuals(l): this equation's columns of its row set.
    const RobinRows& r = rows(s, l);
    const std::vector<double>& face = face_residuals_[static_cast<std::size_t>(s.rows)];
    const std::size_t width = face.size() / std::max<std::size_t>(r.size(), 1);
    const auto rows_count = static_cast<std::ptrdiff_t>(r.size());
    const std::ptrdiff_t* point = r.point.data();
    // The x faces' points are a cache line each: the scatter is worth the threads.
#pragma omp parallel for schedule(static, 256) if (rows_count >= stencil::parallel_min_points)
    for (std::ptrdiff_t row = 0; row < rows_count; ++row)
      for (int c = 0; c < s.ncomp; ++c)
        out[static_cast<std::size_t>(c)][point[row]] =
            face[static_cast<std::size_t>(row) * width + static_cast<std::size_t>(s.face_column + c)];
  }
  if (lv.z_symmetry)
    for (int c = 0; c < s.ncomp; ++c) grid_.fill_ghosts(out[static_cast<std::size_t>(c)], s.parity[static_cast<std::size_t>(c)], l);
}

void FasSolver::residual(int l) {
  for (const Slot& s : slots_) residual_of(s, l);
}

void FasSolver::descend(int l) {
  const int cl = l + 1;
  const Level& fine = grid_.level(l);
  const Level& coarse = grid_.level(cl);
  // With nested boxes the coarse level reaches beyond the fine one: the FAS right-hand side lives
  // on the part the fine box covers, and outside it the coarse box solves its own equation (rhs 0).
  const Level part = covered_part(coarse, fine);
  for (const Slot& s : slots_)
    for (int c = 0; c < s.ncomp; ++c) {
      restrict_injection(fine, part, grid_.data(s.u, c, l), grid_.data(s.u, c, cl), grid_.data(s.old, c, cl));
    }
  fill_ghosts(cl);
  boundary_residuals(l);
  for (std::size_t si = 0; si < slots_.size(); ++si) {
    const Slot& s = slots_[si];
    residual_of(s, l, true);
    // -L(u_H) into the coarse residual array, which serves as scratch here.
    std::vector<double*> minus_lu;
    for (int c = 0; c < s.ncomp; ++c) minus_lu.push_back(grid_.data(s.res, c, cl));
    RelaxArgs a = args(s, cl);
    a.rhs = nullptr;
    s.eq->residual(a, minus_lu.data());
    const std::uint8_t* fixed = a.fixed;
    std::vector<RobinResidual> boundary;
    for (int c = 0; c < s.ncomp; ++c) {
      double* f = grid_.data(s.rhs, c, cl);
      if (fine.inner) std::fill(f, f + coarse.size, 0.0);
      // rhs_H = L_H(u_H) + FW(r_h): the FAS right-hand side. The fine box's faces take the coarse
      // values and are not folded.
      restrict_full_weighting_minus(fine, part, res(s, c, l), minus_lu[static_cast<std::size_t>(c)], f,
                                    s.rows >= 0 && !fine.inner);
      if (s.rows >= 0 && !fine.inner)
        boundary.push_back(
            RobinResidual{grid_.data(s.u, c, cl), s.boundary.u_inf[static_cast<std::size_t>(c)], nullptr, fixed, f});
    }
    if (!boundary.empty()) {
      // Boundary rows: rhs = B(u_H) + injected fine residual; robin_residual with no rhs gives -B
      // (all components in one pass over the rows).
      robin_residual(rows(s, cl), boundary);
      for (int c = 0; c < s.ncomp; ++c) {
        double* f = grid_.data(s.rhs, c, cl);
        const double* r = res(s, c, l);
        for_face_points(coarse, [&](int i, int j, int k) {
          const std::ptrdiff_t p = coarse.at(i, j, k);
          f[p] = r[fine.at(2 * i, 2 * j, 2 * k)] - f[p];
        });
      }
    }
    // With a zero fine right-hand side the coarse one is the relative truncation error tau_h^2h.
    if (l == 0 && rhs_zero_[0]) {
      std::vector<const double*> rhs;
      for (int c = 0; c < s.ncomp; ++c) rhs.push_back(grid_.data(s.rhs, c, cl));
      tau_[si] = rms_interior(s, rhs, part, cl);
    }
  }
  rhs_zero_[static_cast<std::size_t>(cl)] = 0;
}

void FasSolver::correct(int l, bool cubic) {
  const int cl = l + 1;
  for (const Slot& s : slots_) {
    const std::uint8_t* fixed = s.mask >= 0 ? grid_.mask(s.mask, l) : nullptr;
    const Level& fine = grid_.level(l);
    // An inner box's faces follow the coarser box's solution, whatever the equation's outer condition.
    for (int c = 0; c < s.ncomp; ++c)
      (cubic ? prolong_correction_cubic : prolong_correction)(covered_part(grid_.level(cl), fine), fine,
                                                              grid_.data(s.u, c, cl), grid_.data(s.old, c, cl),
                                                              grid_.data(s.u, c, l), fixed, s.rows >= 0 || fine.inner);
  }
  fill_ghosts(l);
}

void FasSolver::cycle(int l, CycleType type) {
  const int coarsest = levels_ - 1;
  if (l == coarsest) {
    coarse_->solve(l);
    return;
  }
  smooth(l, settings_.pre_sweeps);
  descend(l);
  if (type == CycleType::v || l + 1 == coarsest) {
    cycle(l + 1, type);
  } else if (type == CycleType::w) {
    cycle(l + 1, CycleType::w);
    cycle(l + 1, CycleType::w);
  } else {
    cycle(l + 1, CycleType::f);
    cycle(l + 1, CycleType::v);
  }
  correct(l, false);
  smooth(l, settings_.post_sweeps);
}

void FasSolver::prepare() {
  const int levels = levels_;
  std::set<int> coefficients;
  for (const Slot& s : slots_) coefficients.insert(s.coefficients.begin(), s.coefficients.end());
  for (int field : coefficients) {
    const int ncomp = static_cast<int>(grid_.field_info(field).components.size());
    // Full weighting reads the ghost plane below z = 0 (equatorial symmetry): each level's ghosts
    // must be current before it is restricted, or the z = 0 plane is averaged with stale values
    // (that slowed every V-cycle with coefficients: 0.60 against 0.18 per cycle at n = 128).
    for (int l = 0; l < levels; ++l) {
      grid_.fill_ghosts(field, l);
      // On a coarser box, beyond the part the finer box covers, the coefficient keeps the values
      // its plugin gave it there.
      if (l + 1 < levels)
        for (int c = 0; c < ncomp; ++c)
          restrict_full_weighting(grid_.level(l), covered_part(grid_.level(l + 1), grid_.level(l)),
                                  grid_.data(field, c, l), grid_.data(field, c, l + 1));
    }
  }
  // Every level starts from the injected fine state: Dirichlet faces and held points keep the
  // finest level's values, and `old` records the start for the FMG correction.
  for (int l = 0; l < levels; ++l) {
    if (l > 0)
      for (const Slot& s : slots_)
        for (int c = 0; c < s.ncomp; ++c) {
          restrict_injection(grid_.level(l - 1), covered_part(grid_.level(l), grid_.level(l - 1)),
                             grid_.data(s.u, c, l - 1), grid_.data(s.u, c, l), grid_.data(s.old, c, l));
        }
    fill_ghosts(l);
  }
  std::fill(rhs_zero_.begin(), rhs_zero_.end(), 1);
}

SolveReport FasSolver::solve(int cycle_cap) {
  try {
    return solve_cycles(cycle_cap);
  } catch (const RunFailure& failure) {
    // Equations know what a failure of theirs usually means (e.g. the Hamiltonian constraint's
    // fold); the solver only knows that it failed.
    std::string hints;
    for (const Slot& s : slots_)
      if (std::string h = s.eq->failure_hint(); !h.empty()) hints += fmt::format("; {}: {}", s.name, h);
    if (hints.empty()) throw;
    if (dynamic_cast<const core::StepFailure*>(&failure)) throw core::StepFailure(failure.what() + hints);
    throw RunFailure(failure.what() + hints);
  }
}

SolveReport FasSolver::solve_cycles(int cycle_cap) {
  using clock = std::chrono::steady_clock;
  report_ = SolveReport{};
  SolveReport& report = report_;
  const auto solve_start = clock::now();
  // The report is complete whenever solve() leaves, by return or by exception.
  struct Finish {
    SolveReport& r;
    clock::time_point t0;
    ~Finish() {
      r.seconds = std::chrono::duration<double>(clock::now() - t0).count();
      if (r.fine_sweeps > 0 && r.fine_sweep_seconds > 0) r.fine_sweep_seconds /= r.fine_sweeps;
    }
  } finish{report, solve_start};
  for (const Slot& s : slots_) report.equations.push_back(s.name);
  coarse_->reset();
  const int coarsest = levels_ - 1;
  auto start = clock::now();
  prepare();
  auto measure = [&](int number) {
    CycleRecord rec;
    rec.cycle = number;
    boundary_residuals(0);
    for (const Slot& s : slots_) {
      residual_of(s, 0, true);
      std::vector<const double*> r;
      for (int c = 0; c < s.ncomp; ++c) r.push_back(res(s, c, 0));
      rec.residual.push_back(rms_interior(s, r, 0));
    }
    // Nested boxes: each coarser box's residual where it solves its own equation; the worst box
    // counts (the coarse residual arrays are the next descent's scratch).
    for (int l = 1; l < boxes_; ++l)
      for (std::size_t si = 0; si < slots_.size(); ++si) {
        const Slot& s = slots_[si];
        residual_of(s, l);
        std::vector<const double*> r;
        for (int c = 0; c < s.ncomp; ++c) r.push_back(res(s, c, l));
        rec.residual[si] = std::max(rec.residual[si], rms_own(s, r, l));
      }
    rec.tau = tau_;
    rec.seconds = std::chrono::duration<double>(clock::now() - start).count();
    for (double r : rec.residual)
      if (!std::isfinite(r)) fail_nonfinite(number);
    return rec;
  };
  // An outer iteration changes the sources a little per step: an FMG start would replace the last
  // solution by the coarse grids' (truncation-error-sized residuals, measured 3e-3 against 4e-6 on
  // the paper example at n = 64), so a converged solve is continued by cycles alone; optionally
  // (fmg_restart) FMG again when the sources moved so far that the residual is well above the
  // truncation error. Measured on the paper example at n = 64 with one cycle per outer iteration:
  // restarting above 1 tau took 9.7 s, never restarting 8.8 s, for the same 34 iterations.
  bool fmg_start = coarsest == 0 || (settings_.fmg && !(settings_.warm_start && warm_));
  std::optional<CycleRecord> warm_record;
  if (!fmg_start) {
    warm_record = measure(0);
    for (std::size_t s = 0; s < slots_.size() && settings_.fmg && settings_.fmg_restart > 0; ++s)
      fmg_start = fmg_start || warm_record->residual[s] > settings_.fmg_restart * tau_[s];
  }
  warm_ = false;  // until this solve converges
  report.fmg_start = fmg_start;
  if (fmg_start) {
    coarse_->solve(coarsest);
    for (int l = coarsest - 1; l >= 0; --l) {
      correct(l, true);
      for (int c = 0; c < settings_.fmg_cycles; ++c) {
        rhs_zero_[static_cast<std::size_t>(l)] = 1;
        cycle(l, settings_.cycle);
      }
    }
  }
  rhs_zero_[0] = 1;

  auto describe = [&](const CycleRecord& rec) {
    std::string line = rec.cycle == 0 ? std::string(report_.fmg_start ? "after FMG" : "start") : fmt::format("cycle {:2d}", rec.cycle);
    for (std::size_t s = 0; s < slots_.size(); ++s) {
      line += fmt::format(":  {} |r| {:.3e}", slots_[s].name, rec.residual[s]);
      if (rec.tau[s] > 0) line += fmt::format(" |tau| {:.3e} (r/tau {:.2e})", rec.tau[s], rec.residual[s] / rec.tau[s]);
    }
    if (rec.cycle > 0) line += fmt::format(", factor {:.3f}", rec.factor);
    return line + fmt::format(", {:.3f} s", rec.seconds);
  };

  report.history.push_back(fmg_start || !warm_record ? measure(0) : *warm_record);
  log_.detail(describe(report.history.back()));
  if (coarsest == 0) {  // one level: the direct solve is the whole solve
    report.converged = true;
    report.message = "single level solved directly";
    return report;
  }
  const std::vector<double> first = report.history.back().residual;
  int stalled = 0;
  double log_factor_sum = 0;
  for (int number = 1; number <= settings_.max_cycles; ++number) {
    // A stopping signal ends the solve between cycles, unconverged; the core then keeps this state.
    if (core::interrupt_signal() != 0) {
      report.message = fmt::format("interrupted after {} cycles", number - 1);
      return report;
    }
    start = clock::now();
    cycle(0, settings_.cycle);
    CycleRecord rec = measure(number);
    // A copy: the push_back below may move the history, and with it a reference into it.
    const std::vector<double> before = report.history.back().residual;
    for (std::size_t s = 0; s < slots_.size(); ++s)
      rec.factor = std::max(rec.factor, before[s] > 0 ? rec.residual[s] / before[s] : 0.0);
    report.history.push_back(rec);
    report.cycles = number;
    log_.detail(describe(rec));
    log_factor_sum += std::log(std::max(rec.factor, 1e-300));
    report.mean_factor = std::exp(log_factor_sum / number);

    bool converged = number >= settings_.min_cycles;
    for (std::size_t s = 0; s < slots_.size(); ++s) {
      const double r = rec.residual[s];
      const bool small = r <= settings_.tau_factor * rec.tau[s] || r <= settings_.abs_tolerance || r == 0;
      converged = converged && small;
      // Against the truncation error too: a warm start can begin far below it (3e-9 against
      // tau = 9e-3 for the momentum constraint once the others' sources moved), and the coupling
      // lifts it in one cycle without anything diverging.
      if (r > settings_.divergence_factor * std::max({first[s], rec.tau[s], 1e-300}))
        throw core::StepFailure(fmt::format("multigrid: equation '{}' diverges: |r| = {:.3e} after cycle {}, {:.3e} at the start",
                                     slots_[s].name, r, number, first[s]));
    }
    if (converged) {
      report.converged = true;
      warm_ = true;
      report.message = fmt::format("converged in {} cycles, mean factor {:.3f}", number, report.mean_factor);
      return report;
    }
    // Without a warm start the next solve would begin afresh: the cap would only lose the work.
    // A capped solve stops only on a cycle that reduced the residual, and not before min_cycles: a
    // stalling or growing solve goes on to the stall, divergence and max_cycles tests below.
    if (cycle_cap > 0 && settings_.warm_start && number >= std::max(cycle_cap, settings_.min_cycles) && rec.factor < 1) {
      warm_ = true;  // an approximate solution the next solve continues from
      double worst = 0;
      for (std::size_t s = 0; s < slots_.size(); ++s) worst = std::max(worst, rec.residual[s] / std::max(rec.tau[s], 1e-300));
      report.message = fmt::format("stopped after {} cycles (multigrid.loop_cycles), largest r/tau {:.2e}", number, worst);
      return report;
    }
    // Only equations still above their tolerance can stall: one that has reached round-off (the
    // Hamiltonian constraint of a vacuum run, while the shift still converges) stops falling.
    double progress = 0;
    for (std::size_t s = 0; s < slots_.size(); ++s) {
      const double r = rec.residual[s];
      const bool small = r <= settings_.tau_factor * rec.tau[s] || r <= settings_.abs_tolerance || r == 0;
      if (!small) progress = std::max(progress, before[s] > 0 ? r / before[s] : 0.0);
    }
    stalled = progress > settings_.stall_factor ? stalled + 1 : 0;
    if (stalled >= settings_.stall_cycles) {
      std::size_t worst = 0;
      for (std::size_t s = 0; s < slots_.size(); ++s)
        if (rec.residual[s] / std::max(before[s], 1e-300) >= progress) worst = s;
      throw core::StepFailure(fmt::format(
          "multigrid: stagnated: equation '{}' reduced its residual by less than a factor {} in {} cycles in a row "
          "(|r| = {:.3e}, |tau| = {:.3e}, target r/tau = {:.1e})",
          slots_[worst].name, settings_.stall_factor, settings_.stall_cycles, rec.residual[worst], rec.tau[worst],
          settings_.tau_factor));
    }
  }
  throw core::StepFailure(fmt::format("multigrid: not converged in multigrid.max_cycles = {} cycles ({})", settings_.max_cycles,
                               describe(report.history.back())));
}

}  // namespace bhnsid::multigrid
