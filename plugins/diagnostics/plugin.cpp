// The diagnostics plugin: rest mass and ADM mass (volume integral and 1/r falloff) of the solution,
// in physical units, as summary.json scalars after a converged run.
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "axis.hpp"
#include "integrals.hpp"
#include "surface.hpp"

namespace bhnsid::diagnostics {
namespace {

using core::Bin;
using core::Context;

void declare(core::PluginBuilder& b) {
  b.require("grid");
  b.require("equation.hamiltonian");
  b.implements("diagnostics");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability)) {
      // The energy densities integrated for the masses: two finest-level arrays.
      m.add(ctx.plugin(), "densities", fmt::format("two finest-level arrays at {}", layout->describe()),
            2 * layout->field_bytes(core::Storage::finest_only));
    }
  });

  b.schedule(Bin::analysis, "masses", [](Context& ctx) {
     const auto& grid = ctx.services().get<Grid>("grid");
     const auto* fluid = ctx.services().find<Fluid>("hydro");
     const auto* puncture = ctx.services().find<Puncture>("puncture");
     Inputs in;
     in.sigma = fluid ? fluid->sigma() : 1.0;
     in.bh_bare_mass = puncture ? puncture->bare_mass() : 0.0;
     in.centre = fluid ? fluid->centre() : puncture ? puncture->position() : std::array<double, 3>{};
     in.moving = fluid && fluid->moving();
     in.matter = fluid != nullptr;
     const Masses m = masses(grid, in);
     // With a net momentum (a single boosted hole) the AA source reaches beyond the cube like r^-4.
     const double outside = puncture ? outside_aa_mass(grid, in.sigma, puncture->position()) : 0.0;
     ctx.set_scalar("rest_mass", m.rest_mass);
     ctx.set_scalar("adm_mass", m.adm_mass_volume + outside);
     ctx.set_scalar("adm_mass_inside", m.adm_mass_volume);
     ctx.set_scalar("adm_mass_outside", outside);
     ctx.set_scalar("adm_mass_falloff", m.adm_mass_falloff);
     ctx.log().info("M0 = {:.9g}, M_ADM = {:.9g} (volume {:.9g} + outside the cube {:.3g}), {:.9g} (1/r falloff at "
                    "the faces)", m.rest_mass, m.adm_mass_volume + outside, m.adm_mass_volume, outside, m.adm_mass_falloff);
     if (puncture) {
       const double chi = grid.interpolate(grid.data(grid.field_id(fields::chi), 0, 0), Parity{}, 0, puncture->position());
       ctx.set_scalar("chi_puncture", chi);
       ctx.set_scalar("puncture_mass", in.sigma * puncture->bare_mass() * chi);
     }
     for (const auto& [key, value] : deviations(grid)) ctx.set_scalar(key, value);
     if (grid.has_field(fields::ahat)) {
       const SurfaceMomenta s = surface_momenta(grid, in.sigma);
       ctx.set_scalar("momentum_surface_x", s.momentum_x);
       ctx.set_scalar("momentum_surface_y", s.momentum_y);
       ctx.set_scalar("angular_momentum_z", s.angular_momentum_z);
       ctx.log().info("at the faces: P = ({:.9g}, {:.9g}), J_z = {:.9g}", s.momentum_x, s.momentum_y, s.angular_momentum_z);
     }
   }).doc("max deviations from flat space; rest_mass, adm_mass (volume inside the cube + the Bowen-York AA outside it, also given apart as adm_mass_inside, adm_mass_outside), adm_mass_falloff (Robin coefficient of chi); with a puncture chi_puncture "
          "and puncture_mass = sigma Mhat chi(puncture); with Ahat the surface integrals momentum_surface_x/y and "
          "angular_momentum_z; physical units");

  b.schedule(Bin::output, "axis", [](Context& ctx) {
     ctx.write_output("fields_axis.tsv", axis_table(ctx.services().get<Grid>("grid")));
   }).doc("fields_axis.tsv: chi, eta, W, beta, rho0 along the x axis (also after a failure)");
}

}  // namespace
}  // namespace bhnsid::diagnostics

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "diagnostics", "0.1",
                                     "rest mass and ADM mass (volume and falloff) of the solution",
                                     &bhnsid::diagnostics::declare};
  return &info;
}
