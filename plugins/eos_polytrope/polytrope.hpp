#pragma once
// A single polytrope P = K rho0^Gamma (cold, barotropic), in the code's units G = c = 1 with the
// density unit set by K (K = 1 for the paper's stars). Every relation has a closed form.
#include <string>

#include "bhnsid/interfaces/eos.hpp"

namespace bhnsid::eos_polytrope {

class Polytrope final : public Eos {
 public:
  /// Gamma > 1 and K > 0, both finite; anything else throws std::invalid_argument (the plugin
  /// checks the parameters first and reports them as input errors naming the key).
  Polytrope(double gamma, double k);

  std::string describe() const override;
  double pressure(double rho0) const override;                  // K rho0^Gamma
  double specific_internal_energy(double rho0) const override;  // K rho0^(Gamma-1) / (Gamma-1)
  double enthalpy(double rho0) const override;                  // 1 + Gamma/(Gamma-1) K rho0^(Gamma-1)
  double dpressure_drho0(double rho0) const override;           // Gamma K rho0^(Gamma-1)
  double rho0_from_enthalpy(double h) const override;           // [(h-1)(Gamma-1)/(K Gamma)]^(1/(Gamma-1))
  double rho0_from_pressure(double P) const override;           // (P/K)^(1/Gamma)
  EosUnits units() const override;                              // scale free: says how a physical K sets them
  std::vector<PolytropePiece> polytrope_pieces() const override { return {{0.0, k_, gamma_, 0.0}}; }

  double gamma() const { return gamma_; }
  double k() const { return k_; }

 private:
  double gamma_, k_;
};

}  // namespace bhnsid::eos_polytrope
