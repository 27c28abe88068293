// The example plugin (parfiles/demo_poisson1d.yaml): a 1-D Poisson problem relaxed in the core's loop until its
// residual falls below a tolerance, then compared with the exact solution.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "poisson1d.hpp"

namespace bhnsid::demo_poisson1d {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::unique_ptr<Poisson1d> problem;
};

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();

  b.integer("points").doc("grid points on [0, 1], boundaries included").default_value(std::int64_t{65}).at_least(3);
  b.real("omega")
      .doc("SOR over-relaxation factor; 0 picks the optimal 2/(1 + sin(pi h))")
      .default_value(0.0)
      .at_least(0.0)
      .less_than(2.0);
  b.integer("sweeps").doc("red-black SOR sweeps per loop iteration").default_value(std::int64_t{20}).at_least(1);
  b.real("tolerance")
      .doc("converged when max|f + u''| / max|f| is below this (dimensionless)")
      .default_value(1e-10)
      .greater_than(0.0);

  b.schedule(Bin::setup, "allocate", [state](Context& ctx) {
    const auto& p = ctx.params();
    const int n = static_cast<int>(p.integer("points"));
    double omega = p.real("omega");
    if (omega == 0.0) omega = 2.0 / (1.0 + std::sin(std::numbers::pi / (n - 1)));
    state->problem = std::make_unique<Poisson1d>(n, omega);
    ctx.log().info("{} points, SOR omega = {:.6f}", n, omega);
  }).doc("allocate the grid and the source");

  b.schedule(Bin::solve, "relax", [state](Context& ctx) {
    state->problem->relax(static_cast<int>(ctx.params().integer("sweeps")));
  }).doc("red-black SOR sweeps");

  b.check("residual", [state](Context& ctx) {
    const double r = state->problem->relative_residual();
    if (!std::isfinite(r)) throw core::RunFailure(fmt::format("residual is {} at iteration {}", r, ctx.iteration()));
    ctx.set_scalar("residual", r);
    const double tol = ctx.params().real("tolerance");
    return core::Convergence{r < tol, fmt::format("residual {:.3e}, tolerance {:.1e}", r, tol)};
  }).doc("relative residual below the tolerance");

  b.schedule(Bin::analysis, "error", [state](Context& ctx) {
    ctx.set_scalar("error_max", state->problem->error_max());
    ctx.set_scalar("points", state->problem->points());
    ctx.log().info("max |u - sin(pi x)| = {:.6e}", state->problem->error_max());
  }).doc("error against the exact solution sin(pi x)");

  b.schedule(Bin::output, "write_solution", [state](Context& ctx) {
    if (state->problem) ctx.write_output("solution.tsv", state->problem->table());
  }).doc("solution.tsv: x, u, exact");
}

}  // namespace
}  // namespace bhnsid::demo_poisson1d

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "demo_poisson1d", "1.0",
                                     "example: 1-D Poisson problem relaxed in the outer loop",
                                     &bhnsid::demo_poisson1d::declare};
  return &info;
}
