// The multigrid plugin: in every SOLVE it solves all published elliptic equations together with
// FAS multigrid; CHECK reports whether that solve reached its tolerance.
#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "solver.hpp"

namespace bhnsid::multigrid {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::unique_ptr<FasSolver> solver;
  SolveReport report;
  int total_cycles = 0;  ///< finest-level cycles over every solve of the run
};

Settings settings_from(const core::ParamSection& p) {
  Settings s;
  const std::string& cycle = p.string("cycle");
  s.cycle = cycle == "W" ? CycleType::w : cycle == "F" ? CycleType::f : CycleType::v;
  s.pre_sweeps = static_cast<int>(p.integer("pre_sweeps"));
  s.post_sweeps = static_cast<int>(p.integer("post_sweeps"));
  s.omega = p.real("omega");
  s.fmg = p.boolean("fmg");
  s.fmg_cycles = static_cast<int>(p.integer("fmg_cycles"));
  s.warm_start = p.boolean("warm_start");
  s.fmg_restart = p.real("fmg_restart");
  s.tau_factor = p.real("tau_factor");
  s.abs_tolerance = p.real("abs_tolerance");
  s.max_cycles = static_cast<int>(p.integer("max_cycles"));
  s.min_cycles = static_cast<int>(p.integer("min_cycles"));
  s.stall_factor = p.real("stall_factor");
  s.stall_cycles = static_cast<int>(p.integer("stall_cycles"));
  s.divergence_factor = p.real("divergence_factor");
  return s;
}

// The direct solve's Newton steps each refactorise a Jacobian whose LU fill, for a 3-D stencil under
// Eigen's COLAMD ordering, grows about like rows^(4/3) (nested-dissection bound; measured in
// docs/reliability.md); time grows faster still, so very large coarsest levels are refused.
double coarse_lu_bytes(double rows) { return 12.0 * 60.0 * std::pow(rows, 4.0 / 3.0); }

void check_coarse_rows(double rows, const Level& coarsest, const std::string& where) {
  if (rows > max_coarse_rows)
    throw core::InputError(fmt::format(
        "grid.max_levels / grid.min_coarse_intervals: the coarsest level ({} x {} x {} points at {}) gives the "
        "direct solve {:.0f} unknowns, more than the {:.0f} it is bounded to; allow more levels (grid.max_levels = 0) "
        "or a smaller grid.min_coarse_intervals",
        coarsest.nx, coarsest.ny, coarsest.nz, where, rows, max_coarse_rows));
}

std::string history_table(const SolveReport& report) {
  std::string out = "# cycle\tseconds\tfactor";
  for (const auto& name : report.equations) out += fmt::format("\tresidual_{}\ttau_{}", name, name);
  out += "\n";
  for (const CycleRecord& rec : report.history) {
    out += fmt::format("{}\t{:.6e}\t{:.6e}", rec.cycle, rec.seconds, rec.factor);
    for (std::size_t s = 0; s < rec.residual.size(); ++s) out += fmt::format("\t{:.9e}\t{:.9e}", rec.residual[s], rec.tau[s]);
    out += "\n";
  }
  return out;
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.implements("elliptic_solver");
  b.require("grid");
  b.memory(
      [](const Context& ctx, core::MemoryEstimate& m) {
        const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability);
        const double unknowns = m.counted(memory_unknown_components);
        if (!layout || unknowns == 0) return;
        // Per unknown component: FAS right-hand side and saved start on the coarse levels, a residual
        // on every level.
        const double scratch = unknowns * (2 * layout->field_bytes(core::Storage::coarse_levels) +
                                           layout->field_bytes(core::Storage::all_levels));
        m.add(ctx.plugin(), "scratch",
              fmt::format("FAS scratch for {:.0f} unknown components at {}", unknowns, layout->describe()), scratch);
        if (ctx.max_retreats() > 0)
          m.add(ctx.plugin(), "retreat",
                fmt::format("a copy of the finest level's {:.0f} unknown components at {}, for RETREAT (run.max_retreats)",
                            unknowns, layout->describe()),
                unknowns * layout->field_bytes(core::Storage::finest_only));
        const Level& coarsest = layout->levels().back();
        const double rows = unknowns * coarsest.nx * coarsest.ny * coarsest.nz;
        check_coarse_rows(rows, coarsest, layout->describe());
        m.add(ctx.plugin(), "coarse_lu",
              fmt::format("the coarsest level's sparse LU ({:.0f} rows) at {}", rows, layout->describe()),
              coarse_lu_bytes(rows));
      },
      core::MemoryStage::derived);

  b.keyword("cycle", {"V", "W", "F"}).doc("multigrid cycle from the finest level").default_value(std::string("V"));
  b.integer("pre_sweeps").doc("red-black Gauss-Seidel sweeps before descending").default_value(std::int64_t{2}).at_least(0);
  b.integer("post_sweeps").doc("red-black Gauss-Seidel sweeps after the coarse correction").default_value(std::int64_t{2}).at_least(0);
  b.real("omega")
      .doc("over-relaxation of every point Newton step in the red-black sweeps; 1.15 is Yavneh's (1996) "
           "choice for 3-D 7-point stencils, measured 0.06 per V(2,1) cycle on Poisson against 0.13 for 1")
      .default_value(1.15)
      .greater_than(0)
      .less_than(2);
  b.boolean("fmg").doc("start with full multigrid: solve the coarsest level, then interpolate and cycle level by level").default_value(true);
  b.boolean("warm_start")
      .doc("after a converged solve, the next one (an outer iteration's) cycles from its solution instead of "
           "an FMG start")
      .default_value(true);
  b.real("fmg_restart")
      .doc("> 0: a warm start whose residual exceeds this multiple of tau for some equation restarts with FMG "
           "instead; 0: a warm start always continues (measured faster for the binary: docs/performance.md)")
      .default_value(0.0)
      .at_least(0);
  b.integer("loop_cycles")
      .doc("inside the outer loop, at most this many cycles per solve while the sources still move: the solve "
           "stops unconverged (its CHECK says so, the loop goes on) and the next continues from its fields; "
           "0: every solve to the tolerance; ignored without warm_start")
      .default_value(std::int64_t{0})
      .at_least(0);
  b.integer("fmg_cycles").doc("cycles on each level during the FMG start").default_value(std::int64_t{1}).at_least(1);
  b.real("tau_factor")
      .doc("converged when, for every equation, rms residual <= tau_factor * rms truncation-error estimate "
           "|tau_h^2h| (physics-notes §7: the paper's '5,000 times' read as a factor 1/5000-ish)")
      .default_value(1e-3)
      .greater_than(0);
  b.real("abs_tolerance").doc("also converged when every rms residual is below this; 0 turns it off").default_value(0.0).at_least(0);
  b.integer("max_cycles").doc("cycles from the finest level before the solve is declared failed").default_value(std::int64_t{30}).at_least(1);
  b.integer("min_cycles").doc("cycles after the FMG start before convergence is accepted (the first measures tau)").default_value(std::int64_t{1}).at_least(1);
  b.real("stall_factor").doc("a cycle that reduces the residual by less than this factor counts as stalled").default_value(0.95).greater_than(0).at_most(1);
  b.integer("stall_cycles").doc("stalled cycles in a row that end the solve as failed").default_value(std::int64_t{3}).at_least(1);
  b.real("divergence_factor").doc("failed when a residual grows to this multiple of the larger of its start value and |tau|").default_value(1e4).greater_than(1);

  // Made at the first solve, when every equation has been published; a resume makes it earlier.
  const auto make_solver = [state](Context& ctx) {
    if (state->solver) return;
    auto& grid = ctx.services().get<Grid>("grid");
    auto equations = ctx.services().all<EllipticEquation>();
    state->solver = std::make_unique<FasSolver>(grid, equations, settings_from(ctx.params()), ctx.log());
    std::string names;
    for (const Slot& s : state->solver->slots()) names += (names.empty() ? "" : ", ") + s.name;
    ctx.log().info("solving {} equation(s) together: {}; {} of the grid's {} levels", equations.size(), names,
                   state->solver->levels(), grid.num_levels());
  };

  b.checkpoint(
      [state](Context& ctx, core::CheckpointWriter& out) {
        out.put_integer("total_cycles", state->total_cycles);
        out.put_integer("has_solver", state->solver ? 1 : 0);
        out.put("finest_dx", ctx.services().get<Grid>("grid").finest().dx);
        if (state->solver) state->solver->save(out);
      },
      [state, make_solver](Context& ctx, const core::CheckpointReader& in) {
        state->total_cycles = static_cast<int>(in.integer("total_cycles"));
        if (in.integer("has_solver") == 0) return;
        make_solver(ctx);
        state->solver->restore(in);
      });
  // A neighbour's converged fields: continue them with cycles (its tau and coarse Jacobian are
  // this lattice's and nearly this problem's); the cycle count is this run's own. The next coarser
  // run's fields, which the grid interpolates, are continued with cycles too.
  b.warm_start([state, make_solver](Context& ctx, const core::CheckpointReader& in) {
    if (in.integer("has_solver") == 0) return;
    make_solver(ctx);
    if (in.real("finest_dx") == ctx.services().get<Grid>("grid").finest().dx)
      state->solver->restore(in);
    else
      state->solver->warm_start_from_coarser(in);
  });

  b.schedule(Bin::solve, "solve", [state, make_solver](Context& ctx) {
     make_solver(ctx);
     // From the second iteration the start is kept, so that RETREAT can undo a failed solve.
     if (ctx.iteration() > 1 && ctx.max_retreats() > 0) state->solver->keep_start();
     // last_report() also holds the history of a failed solve, for OUTPUT.
     try {
       state->solver->solve(ctx.iteration() > 0 ? static_cast<int>(ctx.params().integer("loop_cycles")) : 0);
     } catch (const core::RunFailure&) {
       state->report = state->solver->last_report();
       throw;
     }
     state->report = state->solver->last_report();
     const SolveReport& r = state->report;
     ctx.show_progress("multigrid_cycles", r.cycles);
     state->total_cycles += r.cycles;
     ctx.set_scalar("multigrid_cycles_total", state->total_cycles);
     ctx.set_scalar("multigrid_factor", r.mean_factor);
     ctx.set_scalar("multigrid_seconds", r.seconds);
     ctx.set_scalar("multigrid_fine_sweep_seconds", r.fine_sweep_seconds);
     const CycleRecord& last = r.history.back();
     for (std::size_t s = 0; s < r.equations.size(); ++s) {
       ctx.set_scalar("multigrid_residual_" + r.equations[s], last.residual[s]);
       ctx.set_scalar("multigrid_tau_" + r.equations[s], last.tau[s]);
     }
   }).doc("FAS multigrid solve of every equation.* service");

  b.schedule(Bin::retreat, "restore_start", [state](Context& ctx) {
     if (!state->solver || !state->solver->restore_start())
       throw core::RunFailure("multigrid: no start of the failed solve was kept to go back to");
     ctx.log().detail("multigrid: the unknowns are back at the start of the failed solve");
   }).doc("the unknowns back to the start of the failed solve (a copy kept from iteration 2 on)");

  b.check("converged", [state](Context&) {
     return core::Convergence{state->report.converged, state->report.message};
   }).doc("the last solve reached its tolerance");

  b.schedule(Bin::output, "write_history", [state](Context& ctx) {
     if (!state->report.history.empty()) ctx.write_output("multigrid_history.tsv", history_table(state->report));
   }).doc("multigrid_history.tsv: residual and tau per equation per cycle");
}

}  // namespace
}  // namespace bhnsid::multigrid

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "multigrid", "1.0",
                                     "FAS multigrid (FMG, V/W/F cycles) for all registered elliptic equations",
                                     &bhnsid::multigrid::declare};
  return &info;
}
