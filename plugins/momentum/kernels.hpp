#pragma once
// The lower-order terms of the momentum constraint for the vector potential W^i, eq. mom_ansatz_hat
// (physics-notes §2.3):
//   lap W^i + (1/3) d_i (d_k W^k) - Zhat^ij d_j(2 q/chi^7) - 16 pi sigma^2 q phi^10 chi^-7 J^i = 0,
//   Zhat^ij d_j(2 q/chi^7) = (LW)^ij (d_j q/q - 7 d_j chi/chi),
// with Zhat = chi^7/(2 q) (LW) and q > 0 the ansatz's weight (the paper's q is eta = alpha phi; any
// positive q solves the momentum constraint, so a lapse that changes sign keeps a positive q),
//   (LW)^ij = d_i W^j + d_j W^i - (2/3) delta_ij d_k W^k,
//   phi = puncture_phi + chi,  J^i = j^i, the star's momentum density.
// They plug into core's stencil::vector_residual/vector_relax (vector_sweep.hpp) as the Lower term
// N^i: it reads W only through centred first differences (never W at the point itself), and J
// depends on the fluid, chi, alpha and the shift but not on W, so the point Jacobian stays
// -(20/3)/h^2 times the identity.
#include <cstddef>
#include <numbers>

#include "bhnsid/interfaces/spacetime.hpp"
#include "bhnsid/interfaces/vector_sweep.hpp"

namespace bhnsid::momentum {

/// Arrays of one level that the lower-order term reads; the momentum density only with matter.
struct Sources {
  const double* chi = nullptr;
  const double* weight = nullptr;  ///< q > 0
  const double* puncture_phi = nullptr;
  MatterSources matter;           ///< j^i from the star, refreshed before the sweep
  std::ptrdiff_t sy = 0, sz = 0;  ///< strides of the level (chi and q are differenced in place)
  double inv_2h = 0;              ///< 1/(2h) of the level
  double source_scale = 1;        ///< 1 except in tests (test_source_scale)
};

/// (LW)^ij = d_i W^j + d_j W^i - (2/3) delta_ij d_k W^k, stored xx, xy, xz, yy, yz, zz (a struct of
/// scalars: GCC 12 does not vectorise an omp simd loop that writes a local array through a pointer).
struct Sym6 {
  double xx, xy, xz, yy, yz, zz;
};

/// (LW)^ij from the gradients of the three components: gx = (d_x W^x, d_y W^x, d_z W^x), and so on.
[[gnu::always_inline]] inline Sym6 conformal_killing(const stencil::Triple& gx, const stencil::Triple& gy,
                                                     const stencil::Triple& gz) {
  const double third_div = (2.0 / 3.0) * (gx.x + gy.y + gz.z);
  return {2.0 * gx.x - third_div, gx.y + gy.x, gx.z + gz.x, 2.0 * gy.y - third_div, gy.z + gz.y, 2.0 * gz.z - third_div};
}

/// N^i = -(LW)^ij (d_j q/q - 7 d_j chi/chi) - 16 pi sigma^2 q phi^10 chi^-7 J^i at one point.
/// Matter = false drops the J term (no fluid); j^i is 0 outside the matter (the star writes
/// it so).
template <bool Matter>
struct MomentumLower {
  Sources s;

  [[gnu::always_inline]] stencil::Triple at(std::ptrdiff_t idx, std::ptrdiff_t i, const stencil::Rows& x, const stencil::Rows& y,
                                            const stencil::Rows& z) const {
    const double h = s.inv_2h;
    const stencil::Triple gx = stencil::gradient(x, i, h), gy = stencil::gradient(y, i, h), gz = stencil::gradient(z, i, h);
    const Sym6 lw = conformal_killing(gx, gy, gz);
    const double* c = s.chi + idx;
    const double* e = s.weight + idx;
    const std::ptrdiff_t sy = s.sy, sz = s.sz;
    const double inv_q = h / e[0], seven_inv_chi = 7.0 * h / c[0];
    // d_j ln(q chi^-7) = d_j q/q - 7 d_j chi/chi by centred differences of the coefficient fields.
    const double gjx = (e[1] - e[-1]) * inv_q - (c[1] - c[-1]) * seven_inv_chi;
    const double gjy = (e[sy] - e[-sy]) * inv_q - (c[sy] - c[-sy]) * seven_inv_chi;
    const double gjz = (e[sz] - e[-sz]) * inv_q - (c[sz] - c[-sz]) * seven_inv_chi;
    stencil::Triple n{-(lw.xx * gjx + lw.xy * gjy + lw.xz * gjz), -(lw.xy * gjx + lw.yy * gjy + lw.yz * gjz),
                      -(lw.xz * gjx + lw.yz * gjy + lw.zz * gjz)};
    if constexpr (Matter) {
      const MatterSources& m = s.matter;
      const double phi = s.puncture_phi[idx] + c[0];
      const double phi2 = phi * phi, phi4 = phi2 * phi2;
      const double inv_chi = 1.0 / c[0], inv_chi2 = inv_chi * inv_chi;
      // 16 pi sigma^2 q phi^10 chi^-7 J^i.
      const double k = 16.0 * std::numbers::pi * m.sigma2 * s.source_scale * e[0] * (phi4 * phi4 * phi2) *
                       (inv_chi2 * inv_chi2 * inv_chi2 * inv_chi);
      n.x -= k * m.momentum[0][idx];
      n.y -= k * m.momentum[1][idx];
      n.z -= k * m.momentum[2][idx];
    }
    return n;
  }
};

}  // namespace bhnsid::momentum
