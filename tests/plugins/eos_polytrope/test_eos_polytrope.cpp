// eos_polytrope: the closed forms, their thermodynamic consistency, the inverses, the vacuum guards,
// the declaration, and bad parameters refused through the real executable. Reference numbers: the
// paper's closure P = rho0^2, eps = rho0, h = 1 + 2 rho0 (physics-notes §3, Gamma = 2, K = 1).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <string>
#include <vector>

#include "bhnsid/core/plugin.hpp"
#include "polytrope.hpp"
#include "process.hpp"

extern "C" const BhnsidPluginInfo* bhnsid_plugin_info();

using bhnsid::eos_polytrope::Polytrope;
using namespace bhnsid::test;
using Catch::Matchers::Contains;

namespace {

// 10 decades of density, 5 points per decade: 1e-10 .. 1 (K = 1 units; the paper's stars have rho0 <~ 0.3).
std::vector<double> densities() {
  std::vector<double> r;
  for (int i = 0; i <= 50; ++i) r.push_back(std::pow(10.0, -10.0 + 0.2 * i));
  return r;
}

const double gammas[] = {4.0 / 3.0, 5.0 / 3.0, 2.0, 2.5, 3.0};

}  // namespace

TEST_CASE("plugins.eos_polytrope.paper_closure", "[plugins][eos_polytrope]") {
  // With the defaults Gamma = 2, K = 1 the EOS is the paper's: P = rho0^2, eps = rho0, h = 1 + 2 rho0,
  // rho0(h) = (h - 1)/2, dP/drho0 = 2 rho0 (physics-notes §3), to rounding.
  const Polytrope eos(2.0, 1.0);
  CHECK(eos.describe() == "polytrope Gamma=2 K=1");
  for (const double rho : {1e-8, 1e-3, 0.1, 0.25, 0.5}) {
    CHECK(eos.pressure(rho) == Approx(rho * rho).epsilon(1e-15));
    CHECK(eos.specific_internal_energy(rho) == Approx(rho).epsilon(1e-15));
    CHECK(eos.enthalpy(rho) == Approx(1 + 2 * rho).epsilon(1e-15));
    CHECK(eos.dpressure_drho0(rho) == Approx(2 * rho).epsilon(1e-15));
    CHECK(eos.rho0_from_enthalpy(1 + 2 * rho) == Approx(rho).epsilon(1e-15 / rho + 1e-15));
    CHECK(eos.energy_density(rho) == Approx(rho * (1 + rho)).epsilon(1e-15));
    CHECK(eos.sound_speed_squared(rho) == Approx(2 * rho / (1 + 2 * rho)).epsilon(1e-15));
  }
}

TEST_CASE("plugins.eos_polytrope.thermodynamic_consistency", "[plugins][eos_polytrope]") {
  // First law at zero temperature: d eps / d rho0 = P / rho0^2. Centred differences with step
  // d = 1e-3 rho0 and d/2: the relative error is below 1e-6 and falls by 4 (3.5 .. 4.5) when the step
  // is halved wherever it is above round-off (1e-10), i.e. the residual is the O(d^2) truncation error of the differences, not an
  // inconsistency of the formulas. Also h = 1 + eps + P/rho0 and dP/drho0 against its difference.
  for (const double gamma : gammas) {
    const Polytrope eos(gamma, 1.0);
    for (const double rho : densities()) {
      auto err = [&](double d) {
        const double fd = (eos.specific_internal_energy(rho + d) - eos.specific_internal_energy(rho - d)) / (2 * d);
        const double exact = eos.pressure(rho) / (rho * rho);
        return std::fabs(fd - exact) / exact;
      };
      const double e1 = err(1e-3 * rho), e2 = err(0.5e-3 * rho);
      INFO("Gamma " << gamma << " rho0 " << rho << " errors " << e1 << " " << e2);
      CHECK(e1 < 1e-6);
      // Gamma = 2 has eps linear in rho0: the differences are exact and only round-off (~1e-13) remains.
      if (e1 > 1e-10) CHECK(e1 / e2 == Approx(4.0).margin(0.5));
      const double h = 1 + eos.specific_internal_energy(rho) + eos.pressure(rho) / rho;
      CHECK(eos.enthalpy(rho) == Approx(h).epsilon(1e-15));
      const double d = 1e-4 * rho;
      const double dp = (eos.pressure(rho + d) - eos.pressure(rho - d)) / (2 * d);
      CHECK(eos.dpressure_drho0(rho) == Approx(dp).epsilon(1e-7));
    }
  }
}

TEST_CASE("plugins.eos_polytrope.inverses_round_trip", "[plugins][eos_polytrope]") {
  // Over 10 decades (rho0 = 1e-10 .. 1) and five Gammas:
  //  - rho0(P(rho0)) = rho0 to 1e-14 (relative);
  //  - h(rho0(h)) = h to 1e-15 (relative), for h = h(rho0);
  //  - rho0(h(rho0)) = rho0 to 1e-12 plus the conditioning floor: h carries rounding DBL_EPSILON h,
  //    and d rho0 / rho0 = dh / (c_s^2 h), so no algorithm taking h (not h - 1) can do better than
  //    ~DBL_EPSILON / c_s^2 (1e-5 at rho0 = 1e-10, Gamma = 2). Where c_s^2 > 1e-3 the bound is 1e-12.
  double worst_p = 0, worst_h = 0, worst_rho_h = 0;
  for (const double gamma : gammas) {
    const Polytrope eos(gamma, 1.0);
    for (const double rho : densities()) {
      const double ep = std::fabs(eos.rho0_from_pressure(eos.pressure(rho)) - rho) / rho;
      const double h = eos.enthalpy(rho);
      const double eh = std::fabs(eos.enthalpy(eos.rho0_from_enthalpy(h)) - h) / h;
      const double er = std::fabs(eos.rho0_from_enthalpy(h) - rho) / rho;
      const double floor = 4 * DBL_EPSILON / eos.sound_speed_squared(rho);
      INFO("Gamma " << gamma << " rho0 " << rho << ": " << ep << " " << eh << " " << er << " floor " << floor);
      CHECK(ep < 1e-14);
      CHECK(eh < 1e-15);
      CHECK(er < 1e-12 + floor);
      if (eos.sound_speed_squared(rho) > 1e-3) worst_rho_h = std::max(worst_rho_h, er);
      worst_p = std::max(worst_p, ep);
      worst_h = std::max(worst_h, eh);
    }
  }
  INFO("worst: rho0(P) " << worst_p << ", h(rho0(h)) " << worst_h << ", rho0(h) where c_s^2 > 1e-3 " << worst_rho_h);
  CHECK(worst_rho_h < 1e-12);
  WARN("eos_polytrope round trips, worst relative error: rho0(P) " << worst_p << ", h(rho0(h)) " << worst_h
                                                                      << ", rho0(h) (c_s^2 > 1e-3) " << worst_rho_h);
}

TEST_CASE("plugins.eos_polytrope.vacuum_monotonicity_and_causality", "[plugins][eos_polytrope]") {
  // Vacuum: P = eps = 0, h = 1 at rho0 <= 0; rho0(h <= 1) = 0, rho0(P <= 0) = 0. P, eps, h increase
  // strictly with rho0 (h only where h - 1 is above rounding). For Gamma <= 2 the sound speed c_s^2 = Gamma P/(rho0 h) stays below 1 for every
  // density (it tends to Gamma - 1); Gamma = 2, K = 1 gives 2 rho0/(1 + 2 rho0).
  const Polytrope eos(2.0, 1.0);
  for (const double rho : {0.0, -1.0}) {
    CHECK(eos.pressure(rho) == 0.0);
    CHECK(eos.specific_internal_energy(rho) == 0.0);
    CHECK(eos.enthalpy(rho) == 1.0);
    CHECK(eos.dpressure_drho0(rho) == 0.0);
    CHECK(eos.sound_speed_squared(rho) == 0.0);
  }
  for (const double h : {1.0, 0.5, -3.0}) CHECK(eos.rho0_from_enthalpy(h) == 0.0);
  for (const double p : {0.0, -1e-30}) CHECK(eos.rho0_from_pressure(p) == 0.0);
  CHECK(std::isnan(eos.rho0_from_enthalpy(std::nan(""))));
  for (const double gamma : gammas) {
    const Polytrope e(gamma, 1.0);
    double p_prev = 0, eps_prev = 0, h_prev = 1;
    for (const double rho : densities()) {
      CHECK(e.pressure(rho) > p_prev);
      CHECK(e.specific_internal_energy(rho) > eps_prev);
      // h - 1 ~ rho0^(Gamma-1) falls below DBL_EPSILON at the lowest densities (Gamma = 3): h = 1 there.
      CHECK(e.enthalpy(rho) >= h_prev);
      if (e.enthalpy(rho) - 1 > 1e-12) CHECK(e.enthalpy(rho) > h_prev);
      p_prev = e.pressure(rho), eps_prev = e.specific_internal_energy(rho), h_prev = e.enthalpy(rho);
      if (gamma <= 2.0) CHECK(e.sound_speed_squared(rho) < 1.0);
    }
  }
  for (const double rho : {1.0, 10.0, 1e6}) CHECK(eos.sound_speed_squared(rho) < 1.0);
}

TEST_CASE("plugins.eos_polytrope.constructor_refuses_bad_values", "[plugins][eos_polytrope]") {
  // The class itself refuses what the plugin's parameter checks refuse.
  CHECK_THROWS_AS(Polytrope(1.0, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(Polytrope(0.5, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(Polytrope(2.0, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(Polytrope(2.0, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(Polytrope(std::nan(""), 1.0), std::invalid_argument);
  CHECK_THROWS_AS(Polytrope(2.0, INFINITY), std::invalid_argument);
}

TEST_CASE("plugins.eos_polytrope.declaration", "[plugins][eos_polytrope]") {
  // The plugin declares a valid interface: implements "eos", gamma = 2 and k = 1 by default.
  const BhnsidPluginInfo* info = bhnsid_plugin_info();
  bhnsid::core::PluginDecl decl;
  decl.name = info->name;
  bhnsid::core::PluginBuilder builder(decl);
  info->declare(builder);
  REQUIRE_NOTHROW(bhnsid::core::validate_declaration(decl));
  CHECK(decl.implements == std::vector<std::string>{"eos"});
  REQUIRE(decl.find_param("gamma"));
  REQUIRE(decl.find_param("k"));
}

TEST_CASE("plugins.eos_polytrope.bad_parameters_refused_by_check", "[plugins][eos_polytrope]") {
  // Through the real executable: `bhnsid check` exits 2 with a message naming the key for Gamma <= 1
  // and K <= 0; the defaults and the paper's values pass (exit 0), and a run publishes and logs the EOS.
  TempDir dir;
  const auto good = dir.write("good.yaml", "plugins: [eos_polytrope]\neos_polytrope:\n  gamma: 2\n  k: 1\n");
  const ProcessResult ok = run_bhnsid({"check", good.string()});
  INFO(ok.out << ok.err);
  CHECK(ok.exit_code == 0);
  const struct {
    const char* yaml;
    const char* key;
  } bad[] = {{"gamma: 1", "eos_polytrope.gamma"},
             {"gamma: 0.5", "eos_polytrope.gamma"},
             {"k: 0", "eos_polytrope.k"},
             {"k: -2", "eos_polytrope.k"}};
  for (const auto& b : bad) {
    const auto par = dir.write("bad.yaml", std::string("plugins: [eos_polytrope]\neos_polytrope:\n  ") + b.yaml + "\n");
    const ProcessResult r = run_bhnsid({"check", par.string()});
    INFO(b.yaml << "\n" << r.out << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains(b.key));
  }
  const auto out = dir.path() / "run";
  const ProcessResult run = run_bhnsid({"run", good.string(), "--output", out.string()});
  INFO(run.out << run.err);
  CHECK(run.exit_code == 0);
  CHECK_THAT(read_file(out / "log.txt"), Contains("polytrope Gamma=2 K=1"));
}
