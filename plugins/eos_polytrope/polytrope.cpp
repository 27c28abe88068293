#include "polytrope.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace bhnsid::eos_polytrope {

Polytrope::Polytrope(double gamma, double k) : gamma_(gamma), k_(k) {
  if (!(std::isfinite(gamma) && gamma > 1.0)) throw std::invalid_argument(fmt::format("Gamma = {}: expected > 1", gamma));
  if (!(std::isfinite(k) && k > 0.0)) throw std::invalid_argument(fmt::format("K = {}: expected > 0", k));
}

EosUnits Polytrope::units() const {
  EosUnits u;
  // P = K rho0^Gamma with G = c = 1 fixes the length unit K^(n/2), n = 1/(Gamma - 1): the star is the
  // same for every K, and a user's physical K sets the scale.
  u.system = fmt::format("G = c = 1, K = {:g}: scale free; for a physical K_phys (in G = c = M_sun = 1 units) every "
                         "length, time and mass is multiplied by (K_phys/K)^(1/(2(Gamma-1))) M_sun (Gamma = {:g})",
                         k_, gamma_);
  return u;
}

std::string Polytrope::describe() const { return fmt::format("polytrope Gamma={:g} K={:g}", gamma_, k_); }

double Polytrope::pressure(double rho0) const { return rho0 <= 0 ? 0.0 : k_ * std::pow(rho0, gamma_); }

double Polytrope::specific_internal_energy(double rho0) const {
  return rho0 <= 0 ? 0.0 : k_ * std::pow(rho0, gamma_ - 1.0) / (gamma_ - 1.0);
}

double Polytrope::enthalpy(double rho0) const {
  return rho0 <= 0 ? 1.0 : 1.0 + gamma_ / (gamma_ - 1.0) * k_ * std::pow(rho0, gamma_ - 1.0);
}

double Polytrope::dpressure_drho0(double rho0) const {
  return rho0 <= 0 ? 0.0 : gamma_ * k_ * std::pow(rho0, gamma_ - 1.0);
}

double Polytrope::rho0_from_enthalpy(double h) const {
  if (h <= 1.0) return 0.0;  // vacuum; a NaN passes through as NaN
  return std::pow((h - 1.0) * (gamma_ - 1.0) / (k_ * gamma_), 1.0 / (gamma_ - 1.0));
}

double Polytrope::rho0_from_pressure(double P) const {
  if (P <= 0.0) return 0.0;
  return std::pow(P / k_, 1.0 / gamma_);
}

}  // namespace bhnsid::eos_polytrope
