#pragma once
// The velocity potential's equation (continuity under helical symmetry), hatted and divided by C_B:
//   dhat_i [ a ( M_ij dhat_j Psitilde - phi^4 B^i ) ] = 0,   a = rho0 phi^2 / (alpha h),
//   M_ij = alpha^2 delta_ij - phi^4 B^i B^j,   B = beta + Omegahat xi,
// degenerate where rho0 -> 0, which carries the surface condition (no mass flux through the
// surface): nothing is imposed there. Discretised as a conservative vertex-centred finite volume
// whose face coefficient is the face average of a with rho0 from the linear reconstruction of the
// enthalpy level set s = htilde - 1 across the face ("rho0 does the cutting", sub-cell accurate);
// tangential derivatives at faces read vertices of the system only. A vertex is in the system when
// one of its six faces has a > 0 (or the caller holds it there); every vertex of the system is also
// coupled to the mean of its neighbours with a weight 1e-7 of the largest a, which fixes the vertices
// whose faces have all closed and keeps the solution continuous as faces open and close. Solved on
// the finest level with BiCGSTAB (GMRES where it breaks down) over the system, the constant fixed at
// the vertex nearest the star's centre; then extended outside the star (s <= 0) by linear
// extrapolation from its own vertices in a band.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::flow_irrotational {

/// The finest-level fields the operator is built from (ghosts filled, so the z = 0 mirror reads).
struct PotentialCoefficients {
  const double* alpha = nullptr;
  const double* phi = nullptr;
  const double* beta[3] = {nullptr, nullptr, nullptr};  ///< null: beta = 0
  const double* level_set = nullptr;                    ///< s = htilde - 1 (< 0 outside the star)
  double omega_hat = 0;
  std::array<double, 3> centre{};  ///< the star's centre: the gauge vertex
  /// The box of vertices that may be physical: [lo, hi] per axis (stored indices).
  std::array<std::array<int, 2>, 3> box{};
  /// Vertices kept in the system and among the extension's sources although the level set no longer
  /// puts them there (null: none); see Irrotational::prepare.
  const std::uint8_t* held_system = nullptr;
  const std::uint8_t* held_source = nullptr;
};

struct PotentialSolve {
  int unknowns = 0;     ///< physical vertices
  int iterations = 0;   ///< BiCGSTAB iterations
  double residual = 0;  ///< relative residual reached
  bool converged = false;
  std::vector<std::uint8_t> system;  ///< the vertices solved for (stored points)
  std::vector<std::uint8_t> source;  ///< the solved vertices the extension started from
};

struct PotentialSettings {
  double tolerance = 1e-10;  ///< relative residual of the linear solve
  int face_samples = 16;     ///< sub-squares per side of a cut face for the face average of rho0
  int max_iterations = 1000;
  /// Most unknowns for the sparse LU fallback (about 1 s at 15,000, 10 s at 44,000 on one core).
  long direct_limit = 30000;
  int extension_cells = 2;   ///< layers about the star (s > 0) filled by linear extrapolation (the rest of the box by means)
  /// Weight, relative to the largest face coefficient, of the mean-value coupling of every vertex to
  /// its neighbours in the system: what fixes the vertices whose faces all have a = 0, and makes
  /// the solution a continuous function of the level set as faces open and close.
  double coupling = 1e-7;
  /// Fraction of each outer step's change of Psitilde taken (1: the whole solve).
  double relaxation = 1.0;
};

/// Solves for Psitilde on the finest level of `grid` (the field `psi`), physical vertices from the
/// level set; returns what the solve did. The source is split as S = S_beta + Omegahat S_xi (one
/// operator, taken at the given Omegahat): `psi_xi` (a finest-level array) receives the rotation's
/// part per unit Omegahat, psi = psi_beta + Omegahat psi_xi; their current values start the solves.
PotentialSolve solve_potential(Grid& grid, int psi, double* psi_xi, const Eos& eos, const PotentialCoefficients& c,
                               const PotentialSettings& settings);

/// Face average of rho0(1 + max(s, 0)) over a square face of side dx on which s is linear: s_f at
/// its centre, slopes g1, g2 along its two axes. 0 where the face lies wholly outside; a midpoint rule
/// on samples x samples sub-squares where the surface cuts it; the midpoint rule where its lowest
/// corner lies deeper than the face's range of s; a linear blend of the two between (continuous in
/// s_f, g1, g2 for any EOS).
double face_average_rho0(const Eos& eos, double s_f, double g1, double g2, double dx, int samples);

}  // namespace bhnsid::flow_irrotational
