#pragma once
// The binary's global quantities (physics-notes §1.4, §6.1), physical (k = 1) units:
//   J      = sigma^2 [xhat_BH Phat_y + sigma^2 Int phi^10 (xhat j^y - yhat j^x) d^3xhat]   (eq. angmom)
//   E_b    = (M_ADM - M_BH - M_NS) / M0,  M_BH = sigma Mhat_BH (bare)      (the paper's)
//   E_b'   = (M_ADM - M_punc - M_NS) / M0, M_punc = sigma Mhat_BH chi(xhat_BH)
//   Omega M0 = Omegahat M0 / sigma,  J / M0^2.
// M_NS is the ADM mass of the isolated TOV star of rest mass M0 (the tov_family service).
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::diagnostics {

/// sigma^4 Int phi^10 (xhat j^y - yhat j^x) d^3xhat on the finest level (the matter's part of J),
/// from the fields matter_momentum, chi and puncture_phi (0 without a hole).
double matter_angular_momentum(const Grid& grid, double sigma);

}  // namespace bhnsid::diagnostics
