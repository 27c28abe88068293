#include "piecewise_polytrope.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "units.hpp"

namespace bhnsid::eos_piecewise_polytrope {

const std::vector<Preset>& presets() {
  // Read, Lackey, Owen & Friedman, Phys. Rev. D 79, 124032 (2009), Table III: log10(p1 / dyn cm^-2),
  // Gamma1, Gamma2, Gamma3 of the best fits (checked against the copy of that table in
  // nrpytutorial's TOV/Piecewise_Polytrope__dict.py, which cites the paper).
  static const std::vector<Preset> list{
      {"sly", "SLy", {34.384, 3.005, 2.988, 2.851}},
      {"apr4", "APR4", {34.269, 2.830, 3.445, 3.348}},
      {"h4", "H4", {34.669, 2.909, 2.246, 2.144}},
      {"ms1", "MS1", {34.858, 3.224, 3.033, 1.325}},
  };
  return list;
}

std::optional<CoreParams> find_preset(const std::string& name) {
  for (const Preset& p : presets())
    if (name == p.name) return p.core;
  return std::nullopt;
}

namespace {

// eps_i(rho) - a_i = K rho^(Gamma-1) / (Gamma-1)
double eps_power(double k, double gamma, double rho) { return k * std::pow(rho, gamma - 1.0) / (gamma - 1.0); }

}  // namespace

PiecewisePolytrope::PiecewisePolytrope(const CoreParams& core, std::string label)
    : core_(core), label_(std::move(label)) {
  const std::array<double, 3> core_gamma{core.gamma1, core.gamma2, core.gamma3};
  for (std::size_t i = 0; i < 3; ++i)
    if (!(std::isfinite(core_gamma[i]) && core_gamma[i] > 1.0))
      throw std::invalid_argument(fmt::format("Gamma{} = {}: expected > 1", i + 1, core_gamma[i]));
  if (!std::isfinite(core.log10_p1)) throw std::invalid_argument("log10 p1 is not finite");

  const double du = units::density_g_cm3;
  // Crust: K in code units from K_cgs (P/c^2 in g/cm^3): P_code = K_cgs du^(Gamma-1) rho_code^Gamma.
  pieces_.resize(7);
  pieces_[0] = {0.0, Crust::k0_cgs * std::pow(du, Crust::gamma[0] - 1.0), Crust::gamma[0], 0.0, 0.0, 1.0};
  for (std::size_t i = 1; i < 4; ++i) {
    const double r = units::density_to_code(Crust::rho_divide_cgs[i - 1]);
    const Piece& prev = pieces_[i - 1];
    pieces_[i].rho_lo = r;
    pieces_[i].gamma = Crust::gamma[i];
    pieces_[i].k = prev.k * std::pow(r, prev.gamma - Crust::gamma[i]);  // continuity of P at r
  }
  // Core: K4 from p1 at rho1, then continuity at rho1 and rho2.
  const double rho1 = units::density_to_code(std::pow(10.0, log10_rho1_cgs));
  const double rho2 = units::density_to_code(std::pow(10.0, log10_rho2_cgs));
  const double p1 = units::pressure_to_code(std::pow(10.0, core.log10_p1));
  const double k4 = p1 / std::pow(rho1, core.gamma1);
  // Junction: K3 rho^G3 = K4 rho^Gamma1.
  const Piece& crust_top = pieces_[3];
  const double junction = std::pow(crust_top.k / k4, 1.0 / (core.gamma1 - crust_top.gamma));
  if (!(std::isfinite(junction) && junction > crust_top.rho_lo && junction < rho1))
    throw std::invalid_argument(fmt::format(
        "the first core piece meets the crust's last piece (P = {:.6g} rho^{}, cgs with P/c^2) at rho = {:.4g} g/cm^3, "
        "outside ({:.6g}, 10^14.7) g/cm^3: the pieces would not follow each other in density",
        Crust::k_table_cgs[2], crust_top.gamma, units::density_to_cgs(junction), Crust::rho_divide_cgs[2]));
  pieces_[4].rho_lo = junction;
  pieces_[4].k = k4;
  pieces_[4].gamma = core.gamma1;
  pieces_[5].rho_lo = rho1;
  pieces_[5].k = k4 * std::pow(rho1, core.gamma1 - core.gamma2);
  pieces_[5].gamma = core.gamma2;
  pieces_[6].rho_lo = rho2;
  pieces_[6].k = pieces_[5].k * std::pow(rho2, core.gamma2 - core.gamma3);
  pieces_[6].gamma = core.gamma3;

  // eps continuous: a_i = a_{i-1} + [K_{i-1} r^(G_{i-1}-1)/(G_{i-1}-1) - K_i r^(G_i-1)/(G_i-1)] at r = rho_lo_i.
  for (std::size_t i = 1; i < pieces_.size(); ++i) {
    Piece& p = pieces_[i];
    const Piece& prev = pieces_[i - 1];
    p.a = prev.a + eps_power(prev.k, prev.gamma, p.rho_lo) - eps_power(p.k, p.gamma, p.rho_lo);
    p.p_lo = p.k * std::pow(p.rho_lo, p.gamma);
    p.h_lo = 1.0 + p.a + p.k * p.gamma / (p.gamma - 1.0) * std::pow(p.rho_lo, p.gamma - 1.0);
  }
}

EosUnits PiecewisePolytrope::units() const {
  EosUnits u;
  u.system = "G = c = M_sun = 1";
  u.length_km = units::length_cm * 1e-5;
  u.time_s = units::time_s;
  u.mass_msun = 1;
  u.density_g_cm3 = units::density_g_cm3;
  return u;
}

std::string PiecewisePolytrope::describe() const {
  return fmt::format(
      "piecewise polytrope {} (Read et al. 2009, SLy crust): log10 p1 = {} dyn/cm^2, Gamma1..3 = {}, {}, {}; "
      "crust-core junction at {:.4g} g/cm^3; G = c = M_sun = 1",
      label_, core_.log10_p1, core_.gamma1, core_.gamma2, core_.gamma3, units::density_to_cgs(junction_density()));
}

std::size_t PiecewisePolytrope::piece_of_density(double rho0) const {
  std::size_t i = pieces_.size() - 1;
  while (i > 0 && rho0 < pieces_[i].rho_lo) --i;
  return i;
}

double PiecewisePolytrope::pressure(double rho0) const {
  if (rho0 <= 0) return 0.0;
  const Piece& p = pieces_[piece_of_density(rho0)];
  return p.k * std::pow(rho0, p.gamma);
}

double PiecewisePolytrope::specific_internal_energy(double rho0) const {
  if (rho0 <= 0) return 0.0;
  const Piece& p = pieces_[piece_of_density(rho0)];
  return p.a + eps_power(p.k, p.gamma, rho0);
}

double PiecewisePolytrope::enthalpy(double rho0) const {
  if (rho0 <= 0) return 1.0;
  const Piece& p = pieces_[piece_of_density(rho0)];
  // 1 + eps + P/rho0 = 1 + a + K Gamma/(Gamma-1) rho0^(Gamma-1)
  return 1.0 + p.a + p.k * p.gamma / (p.gamma - 1.0) * std::pow(rho0, p.gamma - 1.0);
}

double PiecewisePolytrope::dpressure_drho0(double rho0) const {
  if (rho0 <= 0) return 0.0;
  const Piece& p = pieces_[piece_of_density(rho0)];
  return p.gamma * p.k * std::pow(rho0, p.gamma - 1.0);
}

double PiecewisePolytrope::rho0_from_enthalpy(double h) const {
  if (h <= 1.0) return 0.0;  // vacuum; NaN passes through
  std::size_t i = pieces_.size() - 1;
  while (i > 0 && h < pieces_[i].h_lo) --i;
  const Piece& p = pieces_[i];
  // h - 1 - a = K Gamma/(Gamma-1) rho^(Gamma-1); both sides change sign together when Gamma < 1.
  return std::pow((h - 1.0 - p.a) * (p.gamma - 1.0) / (p.k * p.gamma), 1.0 / (p.gamma - 1.0));
}

double PiecewisePolytrope::rho0_from_pressure(double P) const {
  if (P <= 0.0) return 0.0;
  std::size_t i = pieces_.size() - 1;
  while (i > 0 && P < pieces_[i].p_lo) --i;
  const Piece& p = pieces_[i];
  return std::pow(P / p.k, 1.0 / p.gamma);
}

}  // namespace bhnsid::eos_piecewise_polytrope
