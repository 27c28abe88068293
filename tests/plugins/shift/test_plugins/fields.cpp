// TEST ONLY plugin for the shift's tests: it stands in for the hamiltonian, lapse, momentum and hydro
// plugins. It registers chi, eta, alpha, puncture_phi and ahat, publishes a "lapse" (alpha = eta/phi), and fills them on every level with the
// manufactured functions of support/manufactured.hpp (puncture_phi = Mhat/(2 r) from a "puncture"
// service, if any, before every solve), and with `matter` publishes a "star" Fluid whose rho0 and
// velocity make beta_exact the exact solution. ANALYSIS: the error of beta against beta_exact
// (scalars shift_mms_error_max, shift_mms_error_rms, shift_mms_beta_max). OUTPUT: with an excision
// mask, excision_points.tsv lists every held point of every level with its beta.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <string>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "../../../support/test_fluid.hpp"
#include "support/manufactured.hpp"

namespace {

using bhnsid::Grid;
using bhnsid::Level;
using bhnsid::core::Bin;
using bhnsid::core::Context;
using bhnsid::core::TensorKind;
using namespace bhnsid::shift::test;
namespace fields = bhnsid::fields;


const std::vector<TensorKind> scalar{TensorKind::scalar};
const std::vector<TensorKind> vector{TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z};
const std::vector<TensorKind> tensor{TensorKind::tensor_xx, TensorKind::tensor_xy, TensorKind::tensor_xz,
                                     TensorKind::tensor_yy, TensorKind::tensor_yz, TensorKind::tensor_zz};

/// Calls fn(point, array index) at every stored point and ghost of a level (ghost coordinates lie
/// one dx outside; the functions are smooth there and have the fields' parities).
template <class Fn>
void for_all_points(const Level& lv, Fn&& fn) {
  for (int k = -1; k <= lv.nz; ++k)
    for (int j = -1; j <= lv.ny; ++j)
      for (int i = -1; i <= lv.nx; ++i) fn(std::array<double, 3>{lv.x(i), lv.y(j), lv.z(k)}, lv.at(i, j, k));
}

void declare(bhnsid::core::PluginBuilder& b) {
  b.require("grid");
  b.implements("star");
  b.implements("lapse");
  b.boolean("matter").doc("publish the hydro service with the manufactured rho0 and fluid velocity").default_value(true);
  b.boolean("provide_ahat").doc("register ahat (false: show the shift's missing-field error)").default_value(true);

  b.schedule(Bin::startup, "fields", [](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     const int chi = grid.add_field(fields::chi, scalar), eta = grid.add_field(fields::eta, scalar);
     grid.add_field(fields::alpha, scalar);
     ctx.publish<bhnsid::Lapse>("lapse", std::make_shared<bhnsid::test::EtaOverPhiLapse>());
     grid.add_field(fields::puncture_phi, scalar);
     const bool ahat_wanted = ctx.params().boolean("provide_ahat");
     const int ahat = ahat_wanted ? grid.add_field(fields::ahat, tensor, bhnsid::core::TimeParity::odd) : -1;
     for (int l = 0; l < grid.num_levels(); ++l) {
       double* c = grid.data(chi, 0, l);
       double* e = grid.data(eta, 0, l);
       for_all_points(grid.level(l), [&](const std::array<double, 3>& x, std::ptrdiff_t p) {
         c[p] = chi_exact(x).v;
         e[p] = eta_exact(x).v;
         if (ahat >= 0) {
           const std::array<double, 6> a = ahat_exact(x);
           for (int q = 0; q < 6; ++q) grid.data(ahat, q, l)[p] = a[static_cast<std::size_t>(q)];
         }
       });
     }
     if (!ctx.params().boolean("matter")) return;
     auto fluid = std::make_shared<bhnsid::test::FieldVelocityFluid>();
     fluid->sigma_value = mms_sigma;
     const auto [rho0, press, h, vel] = fluid->attach(grid);
     // The finest level only: the shift lists the fluid fields as coefficients, so the multigrid
     // must restrict them to the coarse levels itself.
     for_all_points(grid.finest(), [&](const std::array<double, 3>& x, std::ptrdiff_t p) {
       const FluidPoint f = fluid_exact(x);
       grid.data(rho0, 0, 0)[p] = f.rho0;
       grid.data(press, 0, 0)[p] = f.press;
       grid.data(h, 0, 0)[p] = f.enthalpy;
       for (int c = 0; c < 3; ++c) grid.data(vel, c, 0)[p] = f.velocity[static_cast<std::size_t>(c)];
     });
     ctx.publish<bhnsid::Fluid>("star", fluid);
   })
      .after("grid.create")
      .doc("register and fill chi, eta, puncture_phi, ahat (and the fluid), publish lapse and hydro");

  b.schedule(Bin::setup, "setup", [](Context&) {})
      .doc("nothing: the stand-in's fields and services exist from STARTUP; as the \"lapse\" it is the entry the "
           "shift orders itself after");

  b.schedule(Bin::solve, "puncture_phi", [](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     const auto* hole = ctx.services().find<bhnsid::Puncture>("puncture");
     const int pp = grid.field_id(fields::puncture_phi);
     for (int l = 0; l < grid.num_levels(); ++l) {
       double* out = grid.data(pp, 0, l);
       for_all_points(grid.level(l), [&](const std::array<double, 3>& x, std::ptrdiff_t p) {
         if (!hole) {
           out[p] = 0;
           return;
         }
         const auto c = hole->position();
         out[p] = 0.5 * hole->bare_mass() / std::hypot(x[0] - c[0], x[1] - c[1], x[2] - c[2]);
       });
     }
   })
      .before("elliptic_solver.solve")
      .doc("puncture_phi = Mhat/(2 r) on every level from the current puncture (0 without one)");

  b.schedule(Bin::analysis, "errors", [](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     const Level& lv = grid.finest();
     const int beta = grid.field_id(fields::shift);
     double max_err = 0, sum2 = 0, beta_max = 0;
     long count = 0;
     for (int k = 0; k < lv.nz; ++k)
       for (int j = 0; j < lv.ny; ++j)
         for (int i = 0; i < lv.nx; ++i) {
           const std::array<Jet, 3> ex = beta_exact({lv.x(i), lv.y(j), lv.z(k)});
           for (int c = 0; c < 3; ++c) {
             const double err = grid.data(beta, c, 0)[lv.at(i, j, k)] - ex[static_cast<std::size_t>(c)].v;
             max_err = std::fmax(max_err, std::fabs(err));
             beta_max = std::fmax(beta_max, std::fabs(ex[static_cast<std::size_t>(c)].v));
             sum2 += err * err;
             ++count;
           }
         }
     ctx.set_scalar("shift_mms_error_max", max_err);
     ctx.set_scalar("shift_mms_error_rms", std::sqrt(sum2 / static_cast<double>(count)));
     ctx.set_scalar("shift_mms_beta_max", beta_max);
     ctx.log().info("shift manufactured solution: max error {:.4e}, rms {:.4e} (max |beta| {:.4g})", max_err,
                    std::sqrt(sum2 / static_cast<double>(count)), beta_max);
   }).doc("error of beta against beta_exact on the finest level");

  b.schedule(Bin::output, "excision_table", [](Context& ctx) {
     auto& grid = ctx.services().get<Grid>("grid");
     if (!ctx.services().find<bhnsid::Puncture>("puncture")) return;
     const int mask = grid.mask_id(fields::excision_mask);
     const int beta = grid.field_id(fields::shift);
     std::string out = "# level\ti\tj\tk\tx\ty\tz\tbeta_x\tbeta_y\tbeta_z\n";
     for (int l = 0; l < grid.num_levels(); ++l) {
       const Level& lv = grid.level(l);
       const std::uint8_t* m = grid.mask(mask, l);
       for (int k = -1; k <= lv.nz; ++k)
         for (int j = -1; j <= lv.ny; ++j)
           for (int i = -1; i <= lv.nx; ++i) {
             const std::ptrdiff_t p = lv.at(i, j, k);
             if (!m[p]) continue;
             out += fmt::format("{}\t{}\t{}\t{}\t{:.17g}\t{:.17g}\t{:.17g}\t{:.17g}\t{:.17g}\t{:.17g}\n", l, i, j, k,
                                lv.x(i), lv.y(j), lv.z(k), grid.data(beta, 0, l)[p], grid.data(beta, 1, l)[p],
                                grid.data(beta, 2, l)[p]);
           }
     }
     ctx.write_output("excision_points.tsv", out);
   }).doc("excision_points.tsv: every held point of every level with its beta");
}

}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "shift_test_fields", "1.0",
                                     "test: manufactured chi, eta, ahat, fluid for the shift's tests", &declare};
  return &info;
}
