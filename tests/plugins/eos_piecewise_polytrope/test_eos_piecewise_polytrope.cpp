// eos_piecewise_polytrope: the Read, Lackey, Owen & Friedman (2009) piecewise polytrope. Unit
// conversion, the crust of their Table II, the first law, inverses, continuity at every piece
// boundary, monotonicity, causality of the presets up to their maximum-mass stars (found here with a
// small TOV integration), and bad parameters refused through the real executable.
// Reference numbers: Read et al., Phys. Rev. D 79, 124032 (2009), Table II (crust K_i) and Table III
// (presets). Maximum masses SLy 2.05, APR4 2.21, H4 2.03, MS1 2.77 M_sun: the values quoted for these
// EOS in the literature (Read et al. 2009 list them beside the fits), compared to 3 %.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "bhnsid/core/plugin.hpp"
#include "piecewise_polytrope.hpp"
#include "process.hpp"
#include "units.hpp"

extern "C" const BhnsidPluginInfo* bhnsid_plugin_info();

using namespace bhnsid::eos_piecewise_polytrope;
using namespace bhnsid::test;
using Catch::Matchers::Contains;

namespace {

PiecewisePolytrope make(const std::string& name) { return PiecewisePolytrope(*find_preset(name), name); }

const char* preset_names[] = {"sly", "apr4", "h4", "ms1"};

// 12 decades, 1e4 .. 1e16 g/cm^3, 10 points per decade (irrational offset: never on a boundary).
std::vector<double> densities_code() {
  std::vector<double> r;
  for (int i = 0; i <= 120; ++i) r.push_back(units::density_to_code(std::pow(10.0, 4.0 + 0.1 * i + 0.0123)));
  return r;
}

bool near_boundary(const PiecewisePolytrope& eos, double rho, double rel) {
  for (const auto& p : eos.pieces())
    if (p.rho_lo > 0 && std::fabs(rho - p.rho_lo) < rel * p.rho_lo) return true;
  return false;
}

}  // namespace

TEST_CASE("plugins.eos_piecewise_polytrope.units", "[plugins][eos_piecewise_polytrope]") {
  // G = c = M_sun = 1 from CODATA 2018 G, exact c and the IAU 2015 nominal G M_sun: length unit
  // 1.4766 km, density unit 6.176e17 g/cm^3, pressure unit 5.551e38 dyn/cm^2, M_sun = 1.9884e33 g.
  CHECK(units::length_cm == Approx(1.476625e5).epsilon(1e-6));
  CHECK(units::density_g_cm3 == Approx(6.1758e17).epsilon(1e-4));
  CHECK(units::pressure_dyn_cm2 == Approx(5.5506e38).epsilon(1e-4));
  CHECK(units::m_sun_g == Approx(1.98841e33).epsilon(1e-5));
  CHECK(units::density_to_cgs(units::density_to_code(3e14)) == Approx(3e14).epsilon(1e-15));
  CHECK(units::pressure_to_cgs(units::pressure_to_code(1e34)) == Approx(1e34).epsilon(1e-15));
}

TEST_CASE("plugins.eos_piecewise_polytrope.crust_matches_table_ii", "[plugins][eos_piecewise_polytrope]") {
  // K1..K3 of the crust follow from K0 and continuity of P at Table II's dividing densities; they
  // reproduce the K1..K3 printed in Table II to 2e-4 (measured: 2e-5, 1.0e-4, 1.2e-4). Not better:
  // the table rounds Gamma_i to 5 decimals, and K_i = K_{i-1} rho_i^(Gamma_{i-1} - Gamma_i) turns a
  // rounding of 5e-6 in Gamma into 5e-6 ln(rho_i) ~ 1.3e-4 in K_i. The core's K1 reproduces p1 at
  // rho1, and the crust meets the core between 2.6278e12 and 10^14.7 g/cm^3 for every preset.
  for (const char* name : preset_names) {
    const PiecewisePolytrope eos = make(name);
    const auto& pc = eos.pieces();
    REQUIRE(pc.size() == 7);
    for (std::size_t i = 1; i < 4; ++i) {
      const double k_cgs = pc[i].k / std::pow(units::density_g_cm3, pc[i].gamma - 1.0);
      INFO(name << " crust K" << i << " = " << k_cgs);
      CHECK(k_cgs == Approx(Crust::k_table_cgs[i - 1]).epsilon(2e-4));
    }
    const double p1 = units::pressure_to_cgs(eos.pressure(units::density_to_code(std::pow(10.0, 14.7))));
    CHECK(std::log10(p1) == Approx(find_preset(name)->log10_p1).epsilon(1e-14));
    const double junction = units::density_to_cgs(eos.junction_density());
    INFO(name << " junction " << junction << " g/cm^3");
    CHECK(junction > 2.62780e12);
    CHECK(junction < std::pow(10.0, 14.7));
  }
}

TEST_CASE("plugins.eos_piecewise_polytrope.thermodynamic_consistency", "[plugins][eos_piecewise_polytrope]") {
  // d eps/d rho0 = P/rho0^2 within every piece: centred differences with steps 1e-4 rho0 and half of
  // it (points closer than 1e-3 rho0 to a boundary skipped, where P has a kink) have relative error
  // below 1e-6, and it falls by 4 (3.5 .. 4.5) when the step is halved wherever it is above the
  // round-off level 1e-10: second order, so the formulas are consistent. Also h = 1 + eps + P/rho0.
  for (const char* name : preset_names) {
    const PiecewisePolytrope eos = make(name);
    for (const double rho : densities_code()) {
      if (near_boundary(eos, rho, 1e-3)) continue;
      auto err = [&](double d) {
        const double fd = (eos.specific_internal_energy(rho + d) - eos.specific_internal_energy(rho - d)) / (2 * d);
        const double exact = eos.pressure(rho) / (rho * rho);
        return std::fabs(fd - exact) / exact;
      };
      const double e1 = err(1e-4 * rho), e2 = err(0.5e-4 * rho);
      INFO(name << " rho0 " << units::density_to_cgs(rho) << " g/cm^3, errors " << e1 << " " << e2);
      CHECK(e1 < 1e-6);
      if (e1 > 1e-10) CHECK(e1 / e2 == Approx(4.0).margin(0.5));
      const double h = 1 + eos.specific_internal_energy(rho) + eos.pressure(rho) / rho;
      CHECK(eos.enthalpy(rho) == Approx(h).epsilon(1e-15));
      const double d = 1e-5 * rho;
      CHECK(eos.dpressure_drho0(rho) == Approx((eos.pressure(rho + d) - eos.pressure(rho - d)) / (2 * d)).epsilon(1e-7));
    }
  }
}

TEST_CASE("plugins.eos_piecewise_polytrope.inverses_round_trip", "[plugins][eos_piecewise_polytrope]") {
  // Over 12 decades (1e4 .. 1e16 g/cm^3), every preset:
  //  - rho0(P(rho0)) = rho0 to 1e-13 (relative; the crust piece with Gamma = 0.62 amplifies P's
  //    rounding by 1/Gamma);
  //  - h(rho0(h)) = h to 1e-15;
  //  - rho0(h(rho0)) = rho0 to 1e-12 plus the conditioning floor 4 DBL_EPSILON / c_s^2 (h - 1 is
  //    ~1e-10 in the outer crust, so h itself carries too few digits of it; see the polytrope's test);
  //    in the core (rho0 >= 10^14 g/cm^3) the bound is 1e-12 outright.
  double worst_p = 0, worst_h = 0, worst_core = 0;
  for (const char* name : preset_names) {
    const PiecewisePolytrope eos = make(name);
    for (const double rho : densities_code()) {
      const double ep = std::fabs(eos.rho0_from_pressure(eos.pressure(rho)) - rho) / rho;
      const double h = eos.enthalpy(rho);
      const double eh = std::fabs(eos.enthalpy(eos.rho0_from_enthalpy(h)) - h) / h;
      const double er = std::fabs(eos.rho0_from_enthalpy(h) - rho) / rho;
      const double floor = 4 * DBL_EPSILON / eos.sound_speed_squared(rho);
      INFO(name << " rho0 " << units::density_to_cgs(rho) << " g/cm^3: " << ep << " " << eh << " " << er << " floor "
                << floor);
      CHECK(ep < 1e-13);
      CHECK(eh < 1e-15);
      CHECK(er < 1e-12 + floor);
      if (units::density_to_cgs(rho) >= 1e14) worst_core = std::max(worst_core, er);
      worst_p = std::max(worst_p, ep);
      worst_h = std::max(worst_h, eh);
    }
  }
  CHECK(worst_core < 1e-12);
  WARN("eos_piecewise_polytrope round trips, worst relative error: rho0(P) " << worst_p << ", h(rho0(h)) " << worst_h
                                                                             << ", rho0(h) in the core " << worst_core);
}

TEST_CASE("plugins.eos_piecewise_polytrope.continuity_at_piece_boundaries", "[plugins][eos_piecewise_polytrope]") {
  // At each of the six boundaries (three crust dividing densities, the crust-core junction, rho1,
  // rho2) the formulas of the two neighbouring pieces give the same P, eps and h (relative jump
  // < 1e-12), and the public functions just below and just above the boundary agree as well.
  double worst = 0;
  for (const char* name : preset_names) {
    const PiecewisePolytrope eos = make(name);
    const auto& pc = eos.pieces();
    for (std::size_t i = 1; i < pc.size(); ++i) {
      const double r = pc[i].rho_lo;
      auto P = [&](const auto& p) { return p.k * std::pow(r, p.gamma); };
      auto eps = [&](const auto& p) { return p.a + p.k * std::pow(r, p.gamma - 1) / (p.gamma - 1); };
      const double jp = std::fabs(P(pc[i]) - P(pc[i - 1])) / P(pc[i]);
      const double je = std::fabs(eps(pc[i]) - eps(pc[i - 1])) / eps(pc[i]);
      const double h_lo = 1 + eps(pc[i - 1]) + P(pc[i - 1]) / r;
      const double jh = std::fabs(pc[i].h_lo - h_lo) / h_lo;
      const double below = std::nextafter(r, 0.0), above = std::nextafter(r, 1.0);
      const double jp2 = std::fabs(eos.pressure(above) - eos.pressure(below)) / eos.pressure(r);
      const double je2 =
          std::fabs(eos.specific_internal_energy(above) - eos.specific_internal_energy(below)) / eos.specific_internal_energy(r);
      const double jh2 = std::fabs(eos.enthalpy(above) - eos.enthalpy(below)) / eos.enthalpy(r);
      INFO(name << " boundary " << i << " at " << units::density_to_cgs(r) << " g/cm^3: jumps " << jp << " " << je << " "
                << jh << " / " << jp2 << " " << je2 << " " << jh2);
      CHECK(jp < 1e-12);
      CHECK(je < 1e-12);
      CHECK(jh < 1e-12);
      CHECK(jp2 < 1e-12);
      CHECK(je2 < 1e-12);
      CHECK(jh2 < 1e-12);
      worst = std::max({worst, jp, je, jh, jp2, je2, jh2});
    }
  }
  WARN("eos_piecewise_polytrope worst relative jump at a piece boundary: " << worst);
}

TEST_CASE("plugins.eos_piecewise_polytrope.monotone_and_vacuum", "[plugins][eos_piecewise_polytrope]") {
  // P, eps, h strictly increase over 1e4 .. 1e16 g/cm^3 and across every boundary; eps > 0; the
  // inverses are monotone too; vacuum: rho0 <= 0 gives P = eps = 0, h = 1, and h <= 1, P <= 0 give 0.
  for (const char* name : preset_names) {
    const PiecewisePolytrope eos = make(name);
    double p_prev = 0, e_prev = 0, h_prev = 1, rho_h_prev = 0;
    for (const double rho : densities_code()) {
      const double p = eos.pressure(rho), e = eos.specific_internal_energy(rho), h = eos.enthalpy(rho);
      CHECK(p > p_prev);
      CHECK(e > e_prev);
      CHECK(h > h_prev);
      CHECK(eos.rho0_from_enthalpy(h) > rho_h_prev);
      CHECK(eos.dpressure_drho0(rho) > 0);
      p_prev = p, e_prev = e, h_prev = h, rho_h_prev = eos.rho0_from_enthalpy(h);
    }
    CHECK(eos.pressure(0.0) == 0.0);
    CHECK(eos.specific_internal_energy(-1.0) == 0.0);
    CHECK(eos.enthalpy(0.0) == 1.0);
    CHECK(eos.rho0_from_enthalpy(1.0) == 0.0);
    CHECK(eos.rho0_from_enthalpy(0.3) == 0.0);
    CHECK(eos.rho0_from_pressure(0.0) == 0.0);
    CHECK(eos.rho0_from_pressure(-1.0) == 0.0);
  }
}

namespace {

struct Star {
  double mass, radius;
};

// TOV by RK4 in r from the centre (code units G = c = M_sun = 1) to P = 1e-12 P_c.
Star tov(const bhnsid::Eos& eos, double rho_c) {
  const double pc = eos.pressure(rho_c), p_stop = 1e-12 * pc;
  auto rhs = [&](double r, double m, double p, double& dm, double& dp) {
    const double rho = eos.rho0_from_pressure(p);
    const double e = eos.energy_density(rho);
    dm = 4 * std::numbers::pi * r * r * e;
    dp = -(e + p) * (m + 4 * std::numbers::pi * r * r * r * p) / (r * (r - 2 * m));
  };
  const double dr = 2e-3;
  double r = 1e-6, m = 4.0 / 3.0 * std::numbers::pi * r * r * r * eos.energy_density(rho_c), p = pc;
  while (p > p_stop) {
    double k1m, k1p, k2m, k2p, k3m, k3p, k4m, k4p;
    rhs(r, m, p, k1m, k1p);
    rhs(r + dr / 2, m + dr / 2 * k1m, std::max(p + dr / 2 * k1p, 0.0), k2m, k2p);
    rhs(r + dr / 2, m + dr / 2 * k2m, std::max(p + dr / 2 * k2p, 0.0), k3m, k3p);
    rhs(r + dr, m + dr * k3m, std::max(p + dr * k3p, 0.0), k4m, k4p);
    m += dr / 6 * (k1m + 2 * k2m + 2 * k3m + k4m);
    p += dr / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
    r += dr;
  }
  return {m, r};
}

}  // namespace

TEST_CASE("plugins.eos_piecewise_polytrope.presets_causal_up_to_maximum_mass", "[plugins][eos_piecewise_polytrope]") {
  // For each preset: the maximum-mass TOV star (central densities 10^14.6 .. 10^15.6 g/cm^3, steps of
  // 0.02 dex) has the quoted M_max (see the top of the file) to 3 % (SLy 2.05, APR4 2.21, H4 2.03,
  // MS1 2.77 M_sun; this checks the unit conversion end to end). SLy, H4 and MS1 stay causal
  // (c_s < 1) at every density up to that star's central density, i.e. in every stable star.
  // The APR4 fit does not: its Gamma3 = 3.348 above 1e15 g/cm^3 gives c_s^2 = 1.38 at the centre of
  // its maximum-mass star (measured here); it is causal up to the centre of its 2.0 M_sun star, and
  // the test checks that, and that it indeed exceeds 1 below M_max, so that a change is noticed.
  const struct {
    const char* name;
    double m_max;
    double m_causal;  // c_s < 1 up to the central density of the heaviest scanned star with M <= this
  } cases[] = {{"sly", 2.05, 10}, {"apr4", 2.21, 2.0}, {"h4", 2.03, 10}, {"ms1", 2.77, 10}};
  for (const auto& c : cases) {
    const PiecewisePolytrope eos = make(c.name);
    double best_m = 0, best_rho = 0, causal_rho = 0;
    for (int i = 0; i <= 50; ++i) {
      const double rho_c = units::density_to_code(std::pow(10.0, 14.6 + 0.02 * i));
      const Star s = tov(eos, rho_c);
      if (s.mass > best_m) best_m = s.mass, best_rho = rho_c;
      if (s.mass > best_m - 1e-12 && s.mass <= c.m_causal) causal_rho = rho_c;  // on the stable branch
    }
    double cs2_causal = 0, cs2_max = 0;
    for (int i = 0; i <= 1000; ++i) {  // 1e4 g/cm^3 up to the maximum-mass centre, fine steps
      const double rho = units::density_to_code(1e4) * std::pow(best_rho / units::density_to_code(1e4), i / 1000.0);
      cs2_max = std::max(cs2_max, eos.sound_speed_squared(rho));
      if (rho <= causal_rho) cs2_causal = std::max(cs2_causal, eos.sound_speed_squared(rho));
    }
    INFO(c.name << ": M_max " << best_m << " at rho_c " << units::density_to_cgs(best_rho) << " g/cm^3, max c_s^2 "
                << cs2_max << ", up to " << units::density_to_cgs(causal_rho) << " g/cm^3: " << cs2_causal);
    CHECK(best_m == Approx(c.m_max).epsilon(0.03));
    REQUIRE(causal_rho > 0);
    CHECK(cs2_causal < 1.0);
    if (c.m_causal < 10) CHECK(cs2_max > 1.0);
    WARN(c.name << ": M_max " << best_m << " M_sun at rho_c " << units::density_to_cgs(best_rho)
                << " g/cm^3, max c_s^2 up to it " << cs2_max << ", up to " << units::density_to_cgs(causal_rho)
                << " g/cm^3: " << cs2_causal);
  }
}

TEST_CASE("plugins.eos_piecewise_polytrope.presets_and_constructor", "[plugins][eos_piecewise_polytrope]") {
  // The presets are the Table III rows (log10 p1, Gamma1..3) as cited in presets(); unknown names
  // are not found; the class refuses Gamma <= 1 and a log10 p1 that puts the junction outside
  // (2.6278e12, 10^14.7) g/cm^3 (pieces out of order).
  REQUIRE(presets().size() == 4);
  CHECK(find_preset("sly")->log10_p1 == 34.384);
  CHECK(find_preset("apr4")->gamma2 == 3.445);
  CHECK(find_preset("h4")->gamma3 == 2.144);
  CHECK(find_preset("ms1")->gamma3 == 1.325);
  CHECK_FALSE(find_preset("SLy"));
  CHECK_FALSE(find_preset("custom"));
  CHECK_THAT(make("sly").describe(), Contains("log10 p1 = 34.384"));
  CHECK_THROWS_AS(PiecewisePolytrope({34.384, 1.0, 2.988, 2.851}, "x"), std::invalid_argument);
  CHECK_THROWS_AS(PiecewisePolytrope({34.384, 3.005, 0.9, 2.851}, "x"), std::invalid_argument);
  CHECK_THROWS_AS(PiecewisePolytrope({34.384, 3.005, 2.988, -1}, "x"), std::invalid_argument);
  CHECK_THROWS_AS(PiecewisePolytrope({32.0, 3.005, 2.988, 2.851}, "x"), std::invalid_argument);
  CHECK_THROWS_AS(PiecewisePolytrope({38.0, 3.005, 2.988, 2.851}, "x"), std::invalid_argument);
}

TEST_CASE("plugins.eos_piecewise_polytrope.declaration", "[plugins][eos_piecewise_polytrope]") {
  // A valid declaration that implements "eos", with the preset keyword and the four custom parameters.
  const BhnsidPluginInfo* info = bhnsid_plugin_info();
  bhnsid::core::PluginDecl decl;
  decl.name = info->name;
  bhnsid::core::PluginBuilder builder(decl);
  info->declare(builder);
  REQUIRE_NOTHROW(bhnsid::core::validate_declaration(decl));
  CHECK(decl.implements == std::vector<std::string>{"eos"});
  for (const char* key : {"preset", "log10_p1", "gamma1", "gamma2", "gamma3"}) CHECK(decl.find_param(key));
}

TEST_CASE("plugins.eos_piecewise_polytrope.bad_parameters_refused_by_check", "[plugins][eos_piecewise_polytrope]") {
  // Through the real executable: every preset and a custom SLy pass `bhnsid check` (exit 0); exit 2
  // with the key named for Gamma <= 1, an unknown preset, pieces out of order (log10_p1 = 32 puts the
  // junction at 4e15 g/cm^3, above rho1) and a custom value beside a named preset.
  TempDir dir;
  const std::string head = "plugins: [eos_piecewise_polytrope]\neos_piecewise_polytrope:\n";
  for (const char* good : {"  preset: sly\n", "  preset: apr4\n", "  preset: h4\n", "  preset: ms1\n",
                           "  preset: custom\n  log10_p1: 34.5\n  gamma1: 3\n  gamma2: 2.5\n  gamma3: 2\n"}) {
    const auto par = dir.write("good.yaml", head + good);
    const ProcessResult r = run_bhnsid({"check", par.string()});
    INFO(good << r.out << r.err);
    CHECK(r.exit_code == 0);
  }
  const struct {
    const char* yaml;
    const char* expect;
  } bad[] = {{"  preset: custom\n  gamma1: 1\n", "eos_piecewise_polytrope.gamma1"},
             {"  preset: custom\n  gamma3: 0.8\n", "eos_piecewise_polytrope.gamma3"},
             {"  preset: sly4\n", "eos_piecewise_polytrope.preset"},
             {"  preset: custom\n  log10_p1: 32\n", "eos_piecewise_polytrope.log10_p1 = 32"},
             {"  preset: apr4\n  gamma2: 3\n", "eos_piecewise_polytrope.gamma2 = 3: only used with preset: custom"}};
  for (const auto& b : bad) {
    const auto par = dir.write("bad.yaml", head + b.yaml);
    const ProcessResult r = run_bhnsid({"check", par.string()});
    INFO(b.yaml << r.out << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains(b.expect));
  }
  const auto par = dir.write("run.yaml", head + "  preset: h4\n");
  const auto out = dir.path() / "run";
  const ProcessResult run = run_bhnsid({"run", par.string(), "--output", out.string()});
  INFO(run.out << run.err);
  CHECK(run.exit_code == 0);
  CHECK_THAT(read_file(out / "log.txt"), Contains("piecewise polytrope H4"));
}
