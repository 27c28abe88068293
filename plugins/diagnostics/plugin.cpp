// The diagnostics plugin: rest mass and ADM mass (volume integral and 1/r falloff) of the solution,
// in physical units, as summary.json scalars after a converged run.
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/falloff.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/horizon.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "bhnsid/interfaces/tov_family.hpp"
#include "bhnsid/core/errors.hpp"
#include "axis.hpp"
#include "binary.hpp"
#include "integrals.hpp"
#include "surface.hpp"

namespace bhnsid::diagnostics {
namespace {

using core::Bin;
using core::Context;

/// The end-of-run summary on the terminal: each quantity with its name, symbol, value and a note.
class Summary {
 public:
  void add(const std::string& name, const std::string& symbol, double value, const std::string& note = "") {
    rows_ += fmt::format("\n  {:<30} {:<12} {:>15.9g}  {}", name, symbol, value, note);
  }
  std::string text() const { return rows_; }

 private:
  std::string rows_;
};

/// The binary's quantities (binary.hpp): M_NS and M0/(M0)_max from the TOV family when there is
/// one, J, E_b, E_b', Omega M0, J/M0^2 (physical units); what a run cannot give is left out.
void binary_scalars(Context& ctx, const Grid& grid, const Fluid& fluid, const Puncture* puncture, double adm_mass,
                    double rest_mass, Summary& out) {
  const double sigma = fluid.sigma();
  double j = matter_angular_momentum(grid, sigma);
  double m_bh = 0, m_punc = 0;
  if (puncture) {
    j += sigma * sigma * puncture->position()[0] * puncture->momentum()[1];
    m_bh = sigma * puncture->bare_mass();
    m_punc = m_bh * grid.interpolate(grid.data(grid.field_id(fields::chi), 0, 0), Parity{}, 0, puncture->position());
    ctx.set_scalar("bh_puncture_mass", m_punc);
  }
  const double omega = fluid.omega_hat() / sigma;
  const double x_c = sigma * fluid.centre()[0];
  // The hole's irreducible (apparent-horizon) mass, when a horizon plugin found one.
  const auto* horizon = ctx.services().find<ApparentHorizon>("horizon");
  const double m_irr = horizon ? sigma * horizon->irreducible_mass_hat() : std::nan("");
  ctx.set_scalar("angular_momentum", j);
  ctx.set_scalar("omega", omega);
  ctx.set_scalar("omega_m0", omega * rest_mass);
  ctx.set_scalar("j_over_m0sq", j / (rest_mass * rest_mass));
  ctx.set_scalar("star_center_x", x_c);
  if (puncture) {
    ctx.set_scalar("separation", x_c - sigma * puncture->position()[0]);
    out.add("black hole bare mass", "M_BH", m_bh, fmt::format("Mhat_BH = {:.9g}", puncture->bare_mass()));
    out.add("black hole puncture mass", "M_BH chi", m_punc, "sigma Mhat_BH chi(puncture)");
    out.add("black hole position", "x_BH", sigma * puncture->position()[0],
            fmt::format("xhat_BH = {:.9g}", puncture->position()[0]));
    out.add("black hole momentum", "P^y_BH", sigma * puncture->momentum()[1],
            fmt::format("Phat^y = {:.9g}", puncture->momentum()[1]));
    out.add("separation (coordinate)", "d", x_c - sigma * puncture->position()[0], "x_C - x_BH");
    // P_BH / (M Omega x_BH): 1 for a point mass on a circle about the origin.
    const double x_bh = sigma * puncture->position()[0], p_bh = sigma * puncture->momentum()[1];
    ctx.set_scalar("bh_momentum_ratio_bare", p_bh / (m_bh * omega * x_bh));
    if (std::isfinite(m_irr)) {
      ctx.set_scalar("bh_momentum_ratio_irreducible", p_bh / (m_irr * omega * x_bh));
      out.add("black hole irreducible mass", "M_irr", m_irr,
              fmt::format("P^y_BH/(M_irr Omega x_BH) = {:.6f} (bare mass: {:.6f})", p_bh / (m_irr * omega * x_bh),
                          p_bh / (m_bh * omega * x_bh)));
    }
  }
  out.add("star centre (density max)", "x_C", x_c, fmt::format("xhat_C = {:.9g}", fluid.centre()[0]));
  out.add("orbital angular velocity", "Omega", omega, fmt::format("Omegahat = {:.9g}", fluid.omega_hat()));
  out.add("angular momentum (volume)", "J", j, "the matter's + x_BH P^y_BH");
  out.add("", "Omega M0", omega * rest_mass);
  out.add("", "J/M0^2", j / (rest_mass * rest_mass));
  const auto* family = ctx.services().find<TovFamily>("tov_family");
  if (!family) return;
  const double fraction = rest_mass / family->maximum_rest_mass_star().rest_mass;
  ctx.set_scalar("rest_mass_fraction", fraction);
  out.add("", "M0/(M0)_max", fraction, fmt::format("(M0)_max = {:.9g} of the EOS", family->maximum_rest_mass_star().rest_mass));
  double m_ns = 0;
  try {
    m_ns = family->adm_mass_from_rest_mass(rest_mass);
  } catch (const core::RunFailure& e) {
    ctx.log().info("no M_NS, E_b: {}", e.what());  // M0 above the family's maximum
    return;
  }
  ctx.set_scalar("ns_adm_mass", m_ns);
  ctx.set_scalar("binding_energy", (adm_mass - m_bh - m_ns) / rest_mass);
  out.add("star's isolated ADM mass", "M_NS", m_ns, "the TOV star of the same M0");
  out.add("binding energy", "E_b", (adm_mass - m_bh - m_ns) / rest_mass, "(M_ADM - M_BH - M_NS)/M0, the paper's");
  if (puncture) {
    ctx.set_scalar("binding_energy_puncture", (adm_mass - m_punc - m_ns) / rest_mass);
    out.add("binding energy (puncture mass)", "E_b'", (adm_mass - m_punc - m_ns) / rest_mass,
            "with M_BH chi(puncture)");
    if (std::isfinite(m_irr)) {
      ctx.set_scalar("binding_energy_irreducible", (adm_mass - m_irr - m_ns) / rest_mass);
      out.add("binding energy (irreducible mass)", "E_b,irr", (adm_mass - m_irr - m_ns) / rest_mass,
              "(M_ADM - M_irr - M_NS)/M0");
    }
  }
}

void declare(core::PluginBuilder& b) {
  b.require("grid");
  b.require("equation.hamiltonian");
  b.implements("diagnostics");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    if (const auto* layout = ctx.services().find<GridLayout>(grid_layout_capability)) {
      // The energy density integrated for the ADM mass: one finest-level array.
      m.add(ctx.plugin(), "densities", fmt::format("one finest-level array at {}", layout->describe()),
            layout->field_bytes(core::Storage::finest_only));
    }
  });

  b.schedule(Bin::analysis, "masses", [](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     require_single_box(grid, ctx.plugin());
     const auto* fluid = ctx.services().find<Fluid>("star");
     const auto* puncture = ctx.services().find<Puncture>("puncture");
     Inputs in;
     in.sigma = fluid ? fluid->sigma() : 1.0;
     in.bh_bare_mass = puncture ? puncture->bare_mass() : 0.0;
     in.centre = falloff_centre(fluid, puncture);
     in.matter = fluid != nullptr;
     // The projections of the final fields (the last sweep's may lag them by one sweep).
     if (fluid) fluid->update_sources(grid, 0);
     const Masses m = masses(grid, in);
     const double rest_mass = fluid ? fluid->rest_mass() : 0.0;
     // The AA source beyond the cube: like r^-4 with a net momentum (a single boosted hole), like r^-6
     // once the momenta cancel (a binary); the net momentum is the faces' (surface.hpp).
     SurfaceMomenta faces;
     if (grid.has_field(fields::ahat)) faces = surface_momenta(grid, in.sigma);
     const OutsideMass outside_parts =
         puncture ? outside_aa_mass(grid, in.sigma, puncture->position(),
                                    {faces.momentum_x / in.sigma, faces.momentum_y / in.sigma})
                  : OutsideMass{};
     const double outside = outside_parts.total();
     ctx.set_scalar("rest_mass", rest_mass);
     ctx.set_scalar("adm_mass", m.adm_mass_volume + outside);
     ctx.set_scalar("adm_mass_inside", m.adm_mass_volume);
     ctx.set_scalar("adm_mass_outside", outside);
     ctx.set_scalar("adm_mass_outside_net_momentum", outside_parts.net_momentum);
     ctx.set_scalar("adm_mass_outside_remainder", outside_parts.remainder);
     ctx.set_scalar("adm_mass_falloff", m.adm_mass_falloff);
     ctx.log().detail("M0 = {:.9g}, M_ADM = {:.9g} (volume {:.9g} + outside the cube {:.3g}), {:.9g} (1/r falloff at "
                    "the faces)", rest_mass, m.adm_mass_volume + outside, m.adm_mass_volume, outside, m.adm_mass_falloff);
     if (puncture) {
       const double chi = grid.interpolate(grid.data(grid.field_id(fields::chi), 0, 0), Parity{}, 0, puncture->position());
       ctx.set_scalar("chi_puncture", chi);
       ctx.set_scalar("puncture_mass", in.sigma * puncture->bare_mass() * chi);
     }
     for (const auto& [key, value] : deviations(grid, ctx.services().find<Lapse>("lapse"))) ctx.set_scalar(key, value);
     const double surface = surface_flux_mass(grid, in.sigma, in.bh_bare_mass);
     ctx.set_scalar("adm_mass_surface", surface);
     Summary summary;
     summary.add("ADM mass", "M_ADM", m.adm_mass_volume + outside,
                 fmt::format("volume; Robin falloff {:.9g}, surface flux {:.9g}", m.adm_mass_falloff, surface));
     if (const auto* lapse = ctx.services().find<Lapse>("lapse")) {
       // alpha ~ 1 - M_Komar/r: its 1/r coefficient, extrapolated over cube surfaces (a flux of grad
       // alpha through the faces alone is off by O(M/r_c), several per cent on the paper's boxes).
       // The ratio takes M_ADM from the same fit of phi (its puncture part Mhat/(2 rhat) exact): both
       // 1/r coefficients then carry the same error of the box's Robin faces, which the volume
       // integral adm_mass does not (0.7 % apart for a hole with P = 0.3 M at r_c = 20 M).
       const Level& lv = grid.finest();
       const std::array<double, 3> hole = puncture ? puncture->position() : in.centre;
       const double s_min = enclosing_half_width(lv, fluid ? grid.data(grid.field_id(fields::rho0), 0, 0) : nullptr,
                                                 puncture ? &hole : nullptr);
       const double komar = -in.sigma * falloff_fit(lv, lapse_on(grid, *lapse, 0), 1.0, in.centre, s_min).coefficient;
       const double adm_fit =
           in.sigma * (in.bh_bare_mass + 2.0 * falloff_fit(lv, grid.data(grid.field_id(fields::chi), 0, 0), 1.0, in.centre, s_min).coefficient);
       if (!std::isfinite(komar))
         ctx.log().warn("diagnostics: no komar_mass: fewer than four cube surfaces between half the box and its faces "
                        "enclose the star and the hole (half-width {:.4g} hatted needed, faces at {:.4g})",
                        s_min, lv.half_width());
       ctx.set_scalar("komar_mass", komar);
       ctx.set_scalar("adm_mass_fit", adm_fit);
       ctx.set_scalar("virial_ratio", komar / adm_fit);
       summary.add("Komar mass", "M_Komar", komar,
                   fmt::format("1/r coefficient of alpha; M_Komar/M_ADM = {:.6f} with M_ADM = {:.9g} from the same fit of phi",
                               komar / adm_fit, adm_fit));
     }
     if (fluid) {
       summary.add("rest mass", "M0", rest_mass);
       binary_scalars(ctx, grid, *fluid, puncture, m.adm_mass_volume + outside, rest_mass, summary);
     }
     if (grid.has_field(fields::ahat)) {
       const SurfaceMomenta& s = faces;
       ctx.set_scalar("momentum_surface_x", s.momentum_x);
       ctx.set_scalar("momentum_surface_y", s.momentum_y);
       ctx.set_scalar("angular_momentum_z", s.angular_momentum_z);
       summary.add("angular momentum (faces)", "J_z", s.angular_momentum_z, "surface integral of Ahat");
       summary.add("total linear momentum (faces)", "P^y", s.momentum_y,
                   fmt::format("P^x = {:.3g}; ~0 for a binary", s.momentum_x));
     }
     ctx.log().info("physical quantities (G = c = 1, the EOS's units; hatted = coordinate / sigma):{}", summary.text());
   })
      .after_if_present("horizon.find")
      .doc("max deviations from flat space; rest_mass, adm_mass (volume inside the cube + the Bowen-York AA outside it, also given apart as adm_mass_inside, adm_mass_outside = adm_mass_outside_net_momentum (r^-4) + adm_mass_outside_remainder (r^-6)), adm_mass_falloff (Robin coefficient of chi); with a puncture chi_puncture "
          "and puncture_mass = sigma Mhat chi(puncture); with a star and a hole bh_momentum_ratio_bare = P^y_BH/(M_BH Omega x_BH), and with a horizon bh_momentum_ratio_irreducible and binding_energy_irreducible = (M_ADM - M_irr - M_NS)/M0; with a lapse komar_mass (1/r coefficient of alpha), adm_mass_fit (that of phi) and virial_ratio = komar_mass/adm_mass_fit; with Ahat the surface integrals momentum_surface_x/y and "
          "angular_momentum_z; physical units");

  b.schedule(Bin::output, "axis", [](Context& ctx) {
     ctx.write_output("fields_axis.tsv", axis_table(ctx.services().get<Grid>("grid"), ctx.services().find<Lapse>("lapse")));
   }).doc("fields_axis.tsv: chi, the lapse's regular part and alpha, W, beta, rho0 along the x axis (also after a failure)");
}

}  // namespace
}  // namespace bhnsid::diagnostics

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "diagnostics", "0.1",
                                     "rest mass and ADM mass (volume and falloff) of the solution",
                                     &bhnsid::diagnostics::declare};
  return &info;
}
