#pragma once
// A barotropic (cold) equation of state, published by an EOS plugin under the capability "eos".
// Everything is in the code's units G = c = 1 (and, for the polytropes of the paper, K = 1, which
// fixes the length unit); plugins that take cgs input say how they convert.
//   rho0: rest-mass density; P: pressure; eps: specific internal energy; h = 1 + eps + P/rho0.
// Functions are defined for rho0 >= 0 (vacuum: P = eps = 0, h = 1) and h >= 1.
#include <string>
#include <vector>

#include "bhnsid/core/services.hpp"

namespace bhnsid {

/// One piece of a piecewise polytrope: for rho0_lo <= rho0 (< the next piece's rho0_lo),
/// P = k rho0^gamma and eps = eps_offset + k rho0^(gamma-1) / (gamma-1). What a reader of the
/// output needs to recompute P and eps from rho0 alone.
struct PolytropePiece {
  double rho0_lo = 0, k = 0, gamma = 0, eps_offset = 0;
};

/// What one code unit is, for output metadata; 0 where the EOS is scale free (the K = 1 polytrope:
/// `system` then says how a physical K sets the units).
struct EosUnits {
  std::string system = "G = c = 1";
  double length_km = 0, time_s = 0, mass_msun = 0, density_g_cm3 = 0;
};

class Eos : public core::Service {
 public:
  ~Eos() override;  ///< defined in the core library (see grid.hpp)

  /// Short description for logs and summary files, e.g. "polytrope Gamma=2 K=1".
  virtual std::string describe() const = 0;
  virtual double pressure(double rho0) const = 0;
  virtual double specific_internal_energy(double rho0) const = 0;
  /// Relativistic specific enthalpy h = 1 + eps + P / rho0.
  virtual double enthalpy(double rho0) const = 0;
  /// dP/drho0 at fixed entropy (what the sound speed and Newton steps need).
  virtual double dpressure_drho0(double rho0) const = 0;
  /// Sound speed squared c_s^2 = (dP/drho0) / h.
  double sound_speed_squared(double rho0) const { return rho0 > 0 ? dpressure_drho0(rho0) / enthalpy(rho0) : 0.0; }
  /// Inverse of enthalpy(): rho0 with enthalpy(rho0) = h, for h >= 1 (0 for h <= 1). The Bernoulli
  /// update sets h from the first integral and needs rho0 back.
  virtual double rho0_from_enthalpy(double h) const = 0;
  /// Inverse of pressure(): rho0 with pressure(rho0) = P, for P >= 0.
  virtual double rho0_from_pressure(double P) const = 0;
  virtual EosUnits units() const { return {}; }
  /// The pieces in increasing density when this EOS is a (piecewise) polytrope, else empty: an
  /// output then cannot describe it by formulas and says so.
  virtual std::vector<PolytropePiece> polytrope_pieces() const { return {}; }
  /// Total energy density e = rho0 (1 + eps).
  double energy_density(double rho0) const { return rho0 * (1.0 + specific_internal_energy(rho0)); }
};

}  // namespace bhnsid
