#pragma once
// The piecewise polytrope of Read, Lackey, Owen & Friedman, Phys. Rev. D 79, 124032 (2009): the
// four-piece fit of the SLy crust (their Table II) below three core pieces with dividing densities
// rho1 = 10^14.7 and rho2 = 10^15.0 g/cm^3, set by log10 p1 (p at rho1, dyn/cm^2) and Gamma1..3.
// Within piece i: P = K_i rho0^Gamma_i, eps = a_i + K_i rho0^(Gamma_i-1)/(Gamma_i-1), so that
// d eps = (P/rho0^2) d rho0 holds exactly and P, eps and h are continuous. Everything stored and
// returned is in the code's units G = c = M_sun = 1 (units.hpp).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "bhnsid/interfaces/eos.hpp"

namespace bhnsid::eos_piecewise_polytrope {

/// The three core parameters of Read et al. (2009).
struct CoreParams {
  double log10_p1;  ///< log10 of the pressure at rho1 = 10^14.7 g/cm^3, in dyn/cm^2
  double gamma1, gamma2, gamma3;
};

/// A named fit of Read et al. (2009), Table III.
struct Preset {
  const char* name;  ///< the parameter keyword (lower case)
  const char* label; ///< as the paper writes it
  CoreParams core;
};

/// SLy, APR4, H4, MS1 (Read et al. 2009, Table III).
const std::vector<Preset>& presets();
/// The preset with keyword `name`, or nothing.
std::optional<CoreParams> find_preset(const std::string& name);

/// The fixed crust (Read et al. 2009, Table II, fit to SLy): K0 in cgs with P/c^2 in g/cm^3, i.e.
/// P = K0 c^2 rho^Gamma0 dyn/cm^2 for rho in g/cm^3; Gamma0..3; dividing densities in g/cm^3.
struct Crust {
  static constexpr double k0_cgs = 6.80110e-9;
  static constexpr std::array<double, 4> gamma{1.58425, 1.28733, 0.62223, 1.35692};
  static constexpr std::array<double, 3> rho_divide_cgs{2.44034e7, 3.78358e11, 2.62780e12};
  /// K1..K3 as Table II prints them (cgs, 6 digits); the construction derives them from continuity.
  static constexpr std::array<double, 3> k_table_cgs{1.06186e-6, 5.32697e1, 3.99874e-8};
};

/// Core dividing densities: rho1 = 10^14.7, rho2 = 10^15.0 g/cm^3.
inline constexpr double log10_rho1_cgs = 14.7;
inline constexpr double log10_rho2_cgs = 15.0;

class PiecewisePolytrope final : public Eos {
 public:
  struct Piece {
    double rho_lo;  ///< lower bound of the piece (code units); 0 for the first
    double k, gamma, a;
    double p_lo, h_lo;  ///< P and h at rho_lo
  };

  /// Builds crust + core. Throws std::invalid_argument with a plain-language reason when a Gamma is
  /// not > 1 (or not finite), log10_p1 is not finite, or the crust-core junction (where the last crust
  /// piece's pressure equals the first core piece's) does not lie between the last crust dividing
  /// density and rho1, i.e. the pieces would not follow each other in density.
  PiecewisePolytrope(const CoreParams& core, std::string label);

  std::string describe() const override;
  double pressure(double rho0) const override;
  double specific_internal_energy(double rho0) const override;
  double enthalpy(double rho0) const override;
  double dpressure_drho0(double rho0) const override;
  double rho0_from_enthalpy(double h) const override;
  double rho0_from_pressure(double P) const override;
  EosUnits units() const override;  // G = c = M_sun = 1 (units.hpp)
  std::vector<PolytropePiece> polytrope_pieces() const override {
    std::vector<PolytropePiece> out;
    for (const Piece& p : pieces_) out.push_back({p.rho_lo, p.k, p.gamma, p.a});
    return out;
  }

  const std::vector<Piece>& pieces() const { return pieces_; }
  /// Density (code units) where the crust meets the core.
  double junction_density() const { return pieces_[4].rho_lo; }

 private:
  std::size_t piece_of_density(double rho0) const;
  CoreParams core_;
  std::string label_;
  std::vector<Piece> pieces_;  // 7: four crust, three core, in increasing density
};

}  // namespace bhnsid::eos_piecewise_polytrope
