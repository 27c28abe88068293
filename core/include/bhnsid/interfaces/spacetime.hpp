#pragma once
// What the field-equation plugins (hamiltonian, lapse, and later momentum, shift, ire) share: the
// names of the grid fields through which they read each other, the matter as a hydro plugin
// publishes it ("hydro" capability, Fluid) and the black hole as a puncture plugin publishes it
// ("puncture" capability, Puncture). All in hatted (sigma-rescaled) coordinates, physics-notes §1.3.
#include <array>
#include <cmath>

#include "bhnsid/core/services.hpp"

namespace bhnsid {

/// Shared grid fields. Each is registered by the plugin named in its comment, on all levels.
namespace fields {
inline constexpr const char* chi = "chi";              ///< hamiltonian: regular part of phi (eq. ham_hat)
inline constexpr const char* puncture_phi = "puncture_phi";  ///< hamiltonian: Mhat_BH / (2 rhat_BH), 0 without a hole
inline constexpr const char* aa = "aa_hat";            ///< hamiltonian: sum_ij (Ahat^ij)^2, filled by a curvature plugin
inline constexpr const char* eta = "eta";              ///< lapse: eta = alpha phi (eq. maxslice_hat)
inline constexpr const char* shift = "beta";           ///< shift: beta^i (3 components, time-odd)
inline constexpr const char* rho0 = "rho0";            ///< hydro: rest-mass density (never rescaled)
inline constexpr const char* press = "press";          ///< hydro: pressure
inline constexpr const char* enthalpy = "enthalpy";    ///< hydro: specific enthalpy h (1 in vacuum)
/// hydro: the fluid's coordinate velocity dx^i/dt (Omegahat xi^i for corotation), so that the
/// Eulerian velocity is v^i = (beta^i + fluid_velocity^i) / alpha (physics-notes §1.2).
inline constexpr const char* fluid_velocity = "fluid_velocity";
}  // namespace fields

/// The matter as the field equations see it. The fluid fields above live on every level; the
/// multigrid solver restricts them before each solve, since the equations list them as coefficients.
class Fluid : public core::Service {
 public:
  ~Fluid() override;  ///< defined in the core library (see grid.hpp)
  /// The length unit sigma of the hatted coordinates: x = sigma xhat.
  virtual double sigma() const = 0;
  /// Whether fluid_velocity may be non-zero; false for a static star (W = 1 exactly, faster kernels).
  virtual bool moving() const = 0;
  /// Centre of the 1/r falloff of chi and eta at the outer faces: the density maximum (xhat_C, 0, 0).
  virtual std::array<double, 3> centre() const = 0;
};

/// The black hole (Brandt-Brugmann puncture with a Bowen-York momentum), hatted units.
class Puncture : public core::Service {
 public:
  ~Puncture() override;
  virtual double bare_mass() const = 0;                 ///< Mhat_BH > 0
  virtual std::array<double, 3> position() const = 0;   ///< xhat_BH, never a grid point
  virtual std::array<double, 3> momentum() const = 0;   ///< Phat_BH
};

/// Matter projections of a perfect fluid at one point (physics-notes §1.2, §2.1): energy density
/// rho_E = rho0 h W^2 - P and the trace S = rho0 h (W^2 - 1) + 3P, from W^2 = 1 / (1 - v^2) with
/// v^2 = phi^4 |beta + V|^2 / alpha^2 = phi^6 |beta + V|^2 / eta^2. Outside matter (rho0 = 0) both vanish
/// and W is never needed; a point with v^2 >= 1 is superluminal and gives NaN, which the solver reports.
struct MatterProjections {
  double energy = 0;  ///< rho_E
  double trace = 0;   ///< S
};

inline double lorentz_squared(double phi, double eta, double ux, double uy, double uz) {
  const double phi3 = phi * phi * phi;
  const double v2 = phi3 * phi3 * (ux * ux + uy * uy + uz * uz) / (eta * eta);
  return v2 < 1.0 ? 1.0 / (1.0 - v2) : std::nan("");
}

inline MatterProjections matter_projections(double rho0, double press, double enthalpy, double lorentz2) {
  const double rho_h = rho0 * enthalpy;
  return {rho_h * lorentz2 - press, rho_h * (lorentz2 - 1.0) + 3.0 * press};
}

}  // namespace bhnsid
