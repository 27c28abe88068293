#pragma once
// What the field-equation plugins (hamiltonian, lapse, momentum, shift, ire, diagnostics) share: the
// names of the grid fields through which they read each other, the matter as the star plugin
// publishes it ("star" capability, Fluid; its motion is a flow plugin's, flow.hpp) and the black hole as a puncture plugin publishes it
// ("puncture" capability, Puncture). All in hatted (sigma-rescaled) coordinates, physics-notes §1.3.
// No physics formula lives here: each plugin owns the formulas it uses.
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "bhnsid/core/services.hpp"
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid {

/// Shared grid fields. Each is registered by the plugin named in its comment, on all levels.
namespace fields {
inline constexpr const char* chi = "chi";              ///< hamiltonian: regular part of phi (eq. ham_hat)
inline constexpr const char* puncture_phi = "puncture_phi";  ///< hamiltonian: Mhat_BH / (2 rhat_BH), 0 without a hole
inline constexpr const char* aa = "aa_hat";            ///< hamiltonian: sum_ij (Ahat^ij)^2, filled by a curvature plugin
inline constexpr const char* eta = "eta";              ///< lapse (the paper's): eta = alpha phi (eq. maxslice_hat)
inline constexpr const char* shift = "beta";           ///< shift: beta^i (3 components, time-odd)
inline constexpr const char* wvec = "wvec";            ///< momentum: the vector potential W^i (3 components, time-odd)
/// momentum: the positive weight q of the vector-potential ansatz Zhat^ij = chi^7/(2 q) (LW)^ij (the paper
/// has q = eta, eq. mom_ansatz_hat; any positive q solves the momentum constraint exactly); the finest
/// level holds the q of the last curvature fill, what the IRE reconstructs K_ij with.
inline constexpr const char* ansatz_weight = "wvec_weight";
/// momentum: Ahat^ij = Ahat_BY^ij + Zhat^ij, 6 components xx, xy, xz, yy, yz, zz (time-odd), on every
/// level; it also fills aa_hat from it. Both are refreshed before each field solve.
inline constexpr const char* ahat = "ahat";
inline constexpr const char* excision_mask = "excision";  ///< shift: the cube about the puncture (a grid mask)
inline constexpr const char* rho0 = "rho0";            ///< star: rest-mass density (never rescaled)
inline constexpr const char* press = "press";          ///< star: pressure
inline constexpr const char* enthalpy = "enthalpy";    ///< star: specific enthalpy h (1 in vacuum)
/// star: the matter projections the field equations read (physics-notes §1.2), every level, k = 1
/// units (never rescaled; the hatted equations carry sigma^2): rho_E = n_a n_b T^ab, the trace S of
/// S_ij = gamma_ia gamma_jb T^ab, and j^i = -gamma^ia T_ab n^b (3 components, time-odd). They depend
/// on the unknowns (through W), so the star refills them (through its flow) from the current fields before
/// every sweep (Fluid::update_sources); outside the matter they are 0.
inline constexpr const char* matter_energy = "matter_energy";
inline constexpr const char* matter_trace = "matter_trace";
inline constexpr const char* matter_momentum = "matter_momentum";
/// The matter fields of the star, with their components (memory estimates).
inline constexpr std::array<FieldSize, 6> fluid_sizes{
    {{rho0, 1}, {press, 1}, {enthalpy, 1}, {matter_energy, 1}, {matter_trace, 1}, {matter_momentum, 3}}};
}  // namespace fields

/// The matter as the field equations see it. The equations read only the projections rho_E, S and
/// j^i; how the fluid moves (corotation, an irrotational potential), and so W and v^i, is the flow
/// plugin's business (flow.hpp), and another flow replaces it without touching an equation.
class Fluid : public core::Service {
 public:
  ~Fluid() override;  ///< defined in the core library (see grid.hpp)
  /// The length unit sigma of the hatted coordinates: x = sigma xhat.
  virtual double sigma() const = 0;
  /// The current density maximum (xhat_C, 0, 0), hatted.
  virtual std::array<double, 3> centre() const = 0;
  /// Centre of the 1/r falloff of chi and eta at the outer faces (physics-notes §5.2). The solver
  /// builds its boundary rows once, so a fluid keeps this fixed through a run (its initial xhat_C).
  virtual std::array<double, 3> falloff_centre() const { return centre(); }
  /// Omegahat, the angular velocity of the matter's helical symmetry (0 for a static star).
  virtual double omega_hat() const { return 0.0; }
  /// The physical rest mass M0 = sigma^3 Int rho0 W phi^6 d^3xhat with the current fields.
  virtual double rest_mass() const = 0;
  /// The physical rest mass the initial data will hold, known from SETUP on (before the fields
  /// exist), so that a black hole scaled to the star can be placed before the first field solve.
  virtual double initial_rest_mass() const { return rest_mass(); }
  /// True when the last outer step converged and kept the sources it was solved with: whoever
  /// updates other sources from the fluid (the black hole) then keeps them too, so that the written
  /// fields and all their sources stay a consistent pair.
  virtual bool settled() const { return false; }
  /// The Bernoulli constant C_B (h alpha / W = C_B inside the star for corotation, physics-notes §3),
  /// for the IRE's Bernoulli residual; NaN for a fluid without that first integral.
  virtual double bernoulli_constant() const { return std::nan(""); }
  /// The fields the star and its flow read on every level to form the projections; the equations list
  /// them as coefficients, so that the multigrid solver restricts them before each solve.
  virtual std::vector<std::string> source_inputs() const = 0;
  /// Refills matter_energy, matter_trace and matter_momentum on `level` from the fluid and the
  /// current chi, eta (and beta, where the kinematics need it) of that level: one call per sweep.
  virtual void update_sources(Grid& grid, int level) const = 0;
};

/// The projections of one level as the field equations read them, refreshed by the call.
struct MatterSources {
  const double* energy = nullptr;               ///< rho_E
  const double* trace = nullptr;                ///< S
  const double* momentum[3] = {nullptr, nullptr, nullptr};  ///< j^i
  double sigma2 = 1;                            ///< sigma^2: the hatted equations' matter factor (§1.3)
};

/// Asks the fluid to refill the projections of `level` from the current unknowns and returns them.
inline MatterSources matter_sources(Grid& grid, const Fluid& fluid, int level) {
  fluid.update_sources(grid, level);
  MatterSources m;
  m.energy = grid.data(grid.field_id(fields::matter_energy), 0, level);
  m.trace = grid.data(grid.field_id(fields::matter_trace), 0, level);
  const int j = grid.field_id(fields::matter_momentum);
  for (int c = 0; c < 3; ++c) m.momentum[c] = grid.data(j, c, level);
  m.sigma2 = fluid.sigma() * fluid.sigma();
  return m;
}

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

/// Centre of the 1/r falloff at the outer faces for chi and eta (physics-notes §5.2): the fluid's
/// falloff centre if there is a fluid, else the puncture, else the origin.
inline std::array<double, 3> falloff_centre(const Fluid* fluid, const Puncture* puncture) {
  if (fluid) return fluid->falloff_centre();
  if (puncture) return puncture->position();
  return {0.0, 0.0, 0.0};
}

/// Index of component (a, b) of a symmetric tensor stored as xx, xy, xz, yy, yz, zz.
inline constexpr int sym_index(int a, int b) {
  constexpr int table[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  return table[a][b];
}

}  // namespace bhnsid
