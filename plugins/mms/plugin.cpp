// The mms plugin: elliptic test equations with exact solutions (the method of manufactured
// solutions) for the multigrid solver's tests and the performance benchmark. It publishes one
// EllipticEquation (two for the coupled problem) and measures the solver's answer against the
// exact solution.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "manufactured.hpp"

namespace bhnsid::mms {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::unique_ptr<Manufactured> problem;
};

Vec3 vec3(const std::vector<double>& v) { return {v.at(0), v.at(1), v.at(2)}; }

Settings settings_from(const core::ParamSection& p) {
  Settings s;
  s.problem.problem = problem_from(p.string("problem"));
  s.problem.nonlinear_c = p.real("nonlinear_c");
  s.problem.vector_coupling = p.real("vector_coupling");
  s.problem.ball_mass = p.real("ball_mass");
  s.problem.ball_radius = p.real("ball_radius");
  s.problem.ball_centre = vec3(p.real_vector("ball_centre"));
  s.problem.coupled_a = p.real("coupled_a");
  s.problem.coupled_b = p.real("coupled_b");
  s.excision_radius = p.real("excision_radius");
  s.excision_centre = vec3(p.real_vector("excision_centre"));
  s.robin_centre = vec3(p.real_vector("robin_centre"));
  s.initial_guess = p.real("initial_guess");
  return s;
}

// With c > 0 (the sign of the Hamiltonian constraint's matter term) the linearised operator
// lap + 5 c u^4 loses definiteness once 5 c u^4 reaches the lowest Dirichlet eigenvalue of -lap on
// the cube, 3 pi^2 / (2 r_c)^2; the problem may then have several solutions.
void warn_if_indefinite(const Context& ctx, const ProblemSpec& p) {
  if (p.problem != Problem::nonlinear || p.nonlinear_c <= 0) return;
  const double umax = 1 + NonlinearSolution::amplitude, u4 = umax * umax * umax * umax;
  const double lambda = 3 * std::numbers::pi * std::numbers::pi / (4 * p.half_width * p.half_width);
  if (5 * p.nonlinear_c * u4 >= lambda)
    ctx.log().warn("mms.nonlinear_c = {}: 5 c max(u)^4 = {:.3g} reaches the lowest eigenvalue {:.3g} of -lap on the "
                   "cube; the linearised operator is indefinite and the solution may not be unique",
                   p.nonlinear_c, 5 * p.nonlinear_c * u4, lambda);
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.require("grid");
  b.implements("equation.mms");
  b.implements("equation.mms_partner");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    m.count(memory_unknown_components, 6);
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability)) {
      layout->estimate_field(m, ctx.plugin(), "mms_u", 3);
      layout->estimate_field(m, ctx.plugin(), "mms_source", 3);
      layout->estimate_field(m, ctx.plugin(), "mms_w", 3);
      layout->estimate_field(m, ctx.plugin(), "mms_source_w", 3);
    }
  });

  b.keyword("problem", {"poisson", "nonlinear", "vector", "ball", "coupled"})
      .doc("manufactured problem: poisson (the hypre peer's, needs grid.symmetry = none), nonlinear (lap u + c u^5), "
           "vector (the momentum operator), ball (Newtonian potential, Robin boundary), coupled (two equations)")
      .default_value(std::string("nonlinear"));
  b.real("excision_radius")
      .doc("radius of a sphere whose points are held at the exact solution (excision); 0: none")
      .default_value(0.0)
      .at_least(0);
  b.real_vector("excision_centre")
      .doc("centre of the excision sphere")
      .default_value(std::vector<double>{0, 0, 0})
      .length(3);
  b.real("nonlinear_c")
      .doc("coefficient c of u^5 in the nonlinear problem (1/length^2); c > 0 is the Hamiltonian constraint's sign")
      .default_value(-1.0);
  b.real("vector_coupling")
      .doc("kappa of the term -kappa n^i n_j V^j (n = x/r_c, 1/length^2) added to the vector operator so that its "
           "point update is a genuine 3x3 solve; 0 gives exactly the momentum operator")
      .default_value(0.0)
      .at_least(0);
  b.real("ball_mass").doc("mass M of the ball problem (hatted units, G = 1)").default_value(1.0).greater_than(0);
  b.real("ball_radius")
      .doc("radius R of the ball; the ball must lie inside the cube")
      .default_value(0.5)
      .greater_than(0);
  b.real_vector("ball_centre")
      .doc("centre b of the ball; off the origin so that the boundary sees a dipole (z = 0 with equatorial symmetry)")
      .default_value(std::vector<double>{0.1, 0, 0})
      .length(3);
  b.real_vector("robin_centre")
      .doc("centre of the ball problem's Robin condition (z = 0 with equatorial symmetry); at ball_centre the "
           "condition is exact for the exterior solution, and near a face it moves the coarse levels' rows "
           "(multigrid README)")
      .default_value(std::vector<double>{0, 0, 0})
      .length(3);
  b.real("coupled_a")
      .doc("coefficient a of w in the coupled problem's first equation (1/length^2); a b < 0 keeps the "
           "linearised pair invertible on any grid")
      .default_value(1.0);
  b.real("coupled_b")
      .doc("coefficient b of u^3 in the coupled problem's second equation (1/length^2)")
      .default_value(-1.0);
  b.real("initial_guess")
      .doc("starting value of the unknowns at points not on a Dirichlet face and not excised")
      .default_value(0.0);

  b.schedule(Bin::setup, "setup", [state](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     state->problem = std::make_unique<Manufactured>(grid, settings_from(ctx.params()));
     const ProblemSpec& p = state->problem->exact().spec();
     warn_if_indefinite(ctx, p);
     ctx.publish<EllipticEquation>("equation.mms", state->problem->equation());
     if (auto partner = state->problem->partner()) ctx.publish<EllipticEquation>("equation.mms_partner", partner);
     ctx.log().info("problem {} on the cube |x_i| <= {:.6g}{}", to_string(p.problem), p.half_width,
                    ctx.params().real("excision_radius") > 0 ? ", with an excised sphere" : "");
   }).doc("check the grid, register unknowns and coefficients, fill the sources, publish the equations");

  b.schedule(Bin::initial, "initial_data", [state](Context&) {
     state->problem->set_initial();
   }).doc("exact values on Dirichlet faces and excised points, initial_guess elsewhere");

  b.schedule(Bin::analysis, "errors", [state](Context& ctx) {
     const Errors e = state->problem->errors(0);
     ctx.set_scalar("error_max", e.max);
     ctx.set_scalar("error_rms", e.rms);
     ctx.log().info("max |u - exact| = {:.6e}, rms {:.6e}", e.max, e.rms);
     if (state->problem->partner()) {
       const Errors w = state->problem->errors(1);
       ctx.set_scalar("error_max_partner", w.max);
       ctx.set_scalar("error_rms_partner", w.rms);
       ctx.log().info("partner: max |w - exact| = {:.6e}, rms {:.6e}", w.max, w.rms);
     }
   }).doc("errors against the exact solution on the composite grid (every box outside the box inside it)");

  b.schedule(Bin::output, "write_line", [state](Context& ctx) {
     if (state->problem) ctx.write_output("mms_line.tsv", state->problem->line_table());
   }).doc("mms_line.tsv: the solution and the exact solution along the x axis");
}

}  // namespace
}  // namespace bhnsid::mms

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "mms", "1.0",
                                     "manufactured-solution elliptic test equations with exact solutions",
                                     &bhnsid::mms::declare};
  return &info;
}
