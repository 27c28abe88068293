#pragma once
// A polytrope P = K rho0^Gamma implementing bhnsid::Eos, local to the tov tests so that they do not
// depend on the eos_polytrope plugin's objects. eps = K rho0^(Gamma-1) / (Gamma-1),
// h = 1 + K Gamma/(Gamma-1) rho0^(Gamma-1) (physics-notes section 3).
#include <cmath>
#include <string>

#include "bhnsid/interfaces/eos.hpp"

namespace bhnsid::tov::test {

class Polytrope final : public Eos {
 public:
  Polytrope(double gamma, double k) : g_(gamma), k_(k) {}
  std::string describe() const override { return "test polytrope"; }
  double pressure(double rho) const override { return rho > 0 ? k_ * std::pow(rho, g_) : 0.0; }
  double specific_internal_energy(double rho) const override {
    return rho > 0 ? k_ * std::pow(rho, g_ - 1) / (g_ - 1) : 0.0;
  }
  double enthalpy(double rho) const override { return 1.0 + g_ * specific_internal_energy(rho); }
  double dpressure_drho0(double rho) const override { return rho > 0 ? g_ * k_ * std::pow(rho, g_ - 1) : 0.0; }
  double rho0_from_enthalpy(double h) const override {
    return h > 1 ? std::pow((h - 1) * (g_ - 1) / (k_ * g_), 1.0 / (g_ - 1)) : 0.0;
  }
  double rho0_from_pressure(double p) const override { return p > 0 ? std::pow(p / k_, 1.0 / g_) : 0.0; }

 private:
  double g_, k_;
};

}  // namespace bhnsid::tov::test
