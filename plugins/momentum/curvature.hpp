#pragma once
// The conformal traceless extrinsic curvature Ahat^ij = Ahat_BY^ij + Zhat^ij (physics-notes §2.1,
// §2.6) and AA = sum_ij (Ahat^ij)^2, filled on every level of the grid for the equations that read
// them (hamiltonian and lapse read aa_hat, the shift reads ahat); none of them restricts these fields.
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "bowen_york.hpp"

namespace bhnsid::momentum {

/// Ids of the fields the fill reads (wvec, chi, the ansatz weight q) and writes (ahat, aa).
struct CurvatureFields {
  int wvec = -1, chi = -1, weight = -1;
  int ahat = -1, aa = -1;
};

/// How much the finest level's Ahat moved in one fill: max over points and components of
/// |Ahat_new - Ahat_old|, and max |Zhat_new| for scale (physics-notes §2.1).
struct CurvatureChange {
  double max_change = 0;
  double max_zhat = 0;
};

/// On every level l: ahat = bowen_york(P, xhat_BH, x) (zero without a puncture or with P = 0) +
/// chi^7/(2 q) (LW)^ij, and aa = squared_norm(ahat), ghosts filled by parity. Zhat is computed
/// from the FINEST level's W, chi and q sampled at level l's points (what the multigrid's injection
/// puts on the coarse levels at the start of a solve; the coarse arrays themselves may hold zeros
/// before the first solve), differenced at level l's spacing: centred in the interior and across
/// the z = 0 plane (mirror image by the component's parity), one-sided second order
/// (-3 f0 + 4 f1 - f2)/(2h) on the outer faces. Throws core::RunFailure when the puncture sits within
/// 1e-6 h of a point of some level (1/r^2 there). Returns the change on the finest level.
CurvatureChange fill_curvature(Grid& grid, const CurvatureFields& fields, const Puncture* puncture);

}  // namespace bhnsid::momentum
