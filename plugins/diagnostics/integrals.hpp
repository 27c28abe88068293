#pragma once
// The global quantities of a solution (physics-notes §1.4 and §6.1), in physical (k = 1) units
// (the rest mass M0 is the star's, Fluid::rest_mass, since it needs W):
//   M_ADM = sigma [Mhat_BH + Int (phi^-7 AA/(16 pi) + sigma^2 phi^5 rho_E) d^3xhat]   (volume form)
//   M_ADM = sigma [Mhat_BH + 2 <rhat (chi - 1)>_faces]                    (1/r falloff of chi)
// The falloff form averages rhat (chi - 1), rhat = |xhat - centre|, over the outer faces with
// solid-angle weights about the centre: exact for a monopole, O(1/r_c^2) from the dipole and above.
#include <array>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::diagnostics {

struct Masses {
  double adm_mass_volume = 0;
  double adm_mass_falloff = 0;
};

struct Inputs {
  double sigma = 1;
  double bh_bare_mass = 0;          ///< Mhat_BH, 0 without a hole
  std::array<double, 3> centre{};   ///< centre of the 1/r falloff of chi (the Robin centre)
  bool matter = true;               ///< false: no fluid, no matter term (else rho_E from matter_energy)
};

Masses masses(const Grid& grid, const Inputs& in);

}  // namespace bhnsid::diagnostics
