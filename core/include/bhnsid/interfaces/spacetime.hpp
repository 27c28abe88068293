#pragma once
// What the field-equation plugins (hamiltonian, lapse, and later momentum, shift, ire) share: the
// names of the grid fields through which they read each other, the matter as a hydro plugin
// publishes it ("hydro" capability, Fluid) and the black hole as a puncture plugin publishes it
// ("puncture" capability, Puncture). All in hatted (sigma-rescaled) coordinates, physics-notes §1.3.
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "bhnsid/core/services.hpp"
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid {

/// Shared grid fields. Each is registered by the plugin named in its comment, on all levels.
namespace fields {
inline constexpr const char* chi = "chi";              ///< hamiltonian: regular part of phi (eq. ham_hat)
inline constexpr const char* puncture_phi = "puncture_phi";  ///< hamiltonian: Mhat_BH / (2 rhat_BH), 0 without a hole
inline constexpr const char* aa = "aa_hat";            ///< hamiltonian: sum_ij (Ahat^ij)^2, filled by a curvature plugin
inline constexpr const char* eta = "eta";              ///< lapse: eta = alpha phi (eq. maxslice_hat)
inline constexpr const char* shift = "beta";           ///< shift: beta^i (3 components, time-odd)
inline constexpr const char* wvec = "wvec";            ///< momentum: the vector potential W^i (3 components, time-odd)
/// momentum: Ahat^ij = Ahat_BY^ij + Zhat^ij, 6 components xx, xy, xz, yy, yz, zz (time-odd), on every
/// level; it also fills aa_hat from it. Both are refreshed before each field solve.
inline constexpr const char* ahat = "ahat";
inline constexpr const char* excision_mask = "excision";  ///< shift: the cube about the puncture (a grid mask)
inline constexpr const char* rho0 = "rho0";            ///< hydro: rest-mass density (never rescaled)
inline constexpr const char* press = "press";          ///< hydro: pressure
inline constexpr const char* enthalpy = "enthalpy";    ///< hydro: specific enthalpy h (1 in vacuum)
/// hydro: the fluid's coordinate velocity dx^i/dt (Omegahat xi^i for corotation), so that the
/// Eulerian velocity is v^i = (beta^i + fluid_velocity^i) / alpha (physics-notes §1.2).
inline constexpr const char* fluid_velocity = "fluid_velocity";
/// The fluid fields every equation with matter registers, with their components (memory estimates).
inline constexpr std::array<FieldSize, 4> fluid_sizes{{{rho0, 1}, {press, 1}, {enthalpy, 1}, {fluid_velocity, 3}}};
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
  /// The Bernoulli constant C_B of the current matter (h alpha / lorentz = C_B inside the star for
  /// corotation, physics-notes §3), for the IRE's Bernoulli residual; NaN for a fluid that has none
  /// (the manufactured matter of tests).
  virtual double bernoulli_constant() const { return std::nan(""); }
};

/// The black hole (Brandt-Brugmann puncture with a Bowen-York momentum), hatted units, published
/// by a puncture plugin at STARTUP under "puncture". The values may change between outer
/// iterations (the binary updates them); readers ask at every use.
class Puncture : public core::Service {
 public:
  ~Puncture() override;
  virtual double bare_mass() const = 0;                 ///< Mhat_BH > 0
  virtual std::array<double, 3> position() const = 0;   ///< xhat_BH, never a grid point
  virtual std::array<double, 3> momentum() const = 0;   ///< Phat_BH
};

/// Centre of the 1/r falloff at the outer faces for chi and eta (physics-notes §5.2): the star's
/// density maximum if there is a fluid, else the puncture, else the origin.
inline std::array<double, 3> falloff_centre(const Fluid* fluid, const Puncture* puncture) {
  if (fluid) return fluid->centre();
  if (puncture) return puncture->position();
  return {0.0, 0.0, 0.0};
}

/// The matter arrays of one level as every field equation reads them. Without a fluid the fields
/// still exist (the hamiltonian plugin registers them, zero) and sigma = 1; velocity and shift are
/// set only for moving matter. Without a shift equation shift[c] points at velocity[c] with weight
/// 0, so that coordinate_velocity reads valid memory without a test per point (a conditional load
/// kept the sweeps of moving matter from vectorising).
struct MatterArrays {
  const double* rho0 = nullptr;
  const double* press = nullptr;
  const double* enthalpy = nullptr;
  const double* velocity[3] = {nullptr, nullptr, nullptr};
  const double* shift[3] = {nullptr, nullptr, nullptr};
  double shift_weight = 0;  ///< 1 with a shift equation, 0 without
  double sigma2 = 1;  ///< sigma^2: the matter terms of the hatted equations carry it (§1.3)
  bool moving = false;

  /// beta^i + V^i at array index idx (moving matter only).
  double coordinate_velocity(int c, std::ptrdiff_t idx) const { return velocity[c][idx] + shift_weight * shift[c][idx]; }
};

/// The arrays for an explicit sigma and motion (diagnostics, tests).
inline MatterArrays matter_arrays(const Grid& grid, double sigma, bool moving, int level) {
  MatterArrays m;
  m.rho0 = grid.data(grid.field_id(fields::rho0), 0, level);
  m.press = grid.data(grid.field_id(fields::press), 0, level);
  m.enthalpy = grid.data(grid.field_id(fields::enthalpy), 0, level);
  m.sigma2 = sigma * sigma;
  m.moving = moving;
  if (m.moving) {
    const int vel = grid.field_id(fields::fluid_velocity);
    const int beta = grid.has_field(fields::shift) ? grid.field_id(fields::shift) : -1;
    for (int c = 0; c < 3; ++c) {
      m.velocity[c] = grid.data(vel, c, level);
      m.shift[c] = beta >= 0 ? grid.data(beta, c, level) : m.velocity[c];
    }
    m.shift_weight = beta >= 0 ? 1.0 : 0.0;
  }
  return m;
}

inline MatterArrays matter_arrays(const Grid& grid, const Fluid* fluid, int level) {
  return matter_arrays(grid, fluid ? fluid->sigma() : 1.0, fluid && fluid->moving(), level);
}

/// Index of component (a, b) of a symmetric tensor stored as xx, xy, xz, yy, yz, zz.
inline constexpr int sym_index(int a, int b) {
  constexpr int table[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  return table[a][b];
}

/// The Bowen-York tensor at x (physics-notes §2.6; hatted, with Phat):
///   Ahat_BY^ij = 3/(2 r^2) [P^i n^j + P^j n^i - (delta^ij - n^i n^j)(P.n)],  n = (x - x_BH)/r.
/// Traceless and divergence-free for r > 0; r = 0 is never asked (the puncture is off the grid).
inline std::array<double, 6> bowen_york(const std::array<double, 3>& mom, const std::array<double, 3>& x_bh,
                                        const std::array<double, 3>& x) {
  const double d[3] = {x[0] - x_bh[0], x[1] - x_bh[1], x[2] - x_bh[2]};
  const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], r = std::sqrt(r2);
  const double n[3] = {d[0] / r, d[1] / r, d[2] / r};
  const double pn = mom[0] * n[0] + mom[1] * n[1] + mom[2] * n[2];
  const double c = 1.5 / r2;
  // Written out (no loops): a loop nest here keeps every grid loop that calls this scalar.
  auto component = [&](int a, int b) {
    return c * (mom[a] * n[b] + mom[b] * n[a] - ((a == b ? 1.0 : 0.0) - n[a] * n[b]) * pn);
  };
  const std::array<double, 6> out = {component(0, 0), component(0, 1), component(0, 2),
                                     component(1, 1), component(1, 2), component(2, 2)};
  return out;
}

/// sum_ij (A^ij)^2 of a symmetric tensor stored as xx, xy, xz, yy, yz, zz.
inline double squared_norm(const std::array<double, 6>& t) {
  return t[0] * t[0] + t[3] * t[3] + t[5] * t[5] + 2.0 * (t[1] * t[1] + t[2] * t[2] + t[4] * t[4]);
}

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
  // A constant, not std::nan(""): that is a library call, and a call keeps the sweeps unvectorised.
  return v2 < 1.0 ? 1.0 / (1.0 - v2) : std::numeric_limits<double>::quiet_NaN();
}

/// The momentum density j^i = rho0 h W^2 v^i, v^i = (beta^i + V^i)/alpha (physics-notes §1.2).
inline double momentum_density(double rho0, double enthalpy, double lorentz2, double u_i, double alpha) {
  return rho0 * enthalpy * lorentz2 * u_i / alpha;
}

inline MatterProjections matter_projections(double rho0, double press, double enthalpy, double lorentz2) {
  const double rho_h = rho0 * enthalpy;
  return {rho_h * lorentz2 - press, rho_h * (lorentz2 - 1.0) + 3.0 * press};
}

}  // namespace bhnsid
