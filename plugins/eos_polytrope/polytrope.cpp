#include "polytrope.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace bhnsid::eos_polytrope {

Polytrope::Polytrope(double gamma, double k) : gamma_(gamma), k_(k) {
  if (!(std::isfinite(gamma) && gamma > 1.0)) throw std::invalid_argument(fmt::format("Gamma = {}: expected > 1", gamma));
  if (!(std::isfinite(k) && k > 0.0)) throw std::invalid_argument(fmt::format("K = {}: expected > 0", k));
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
