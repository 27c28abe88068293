#pragma once
// The lower-order terms of the momentum constraint for the vector potential W^i, eq. mom_ansatz_hat
// (physics-notes §2.3):
//   lap W^i + (1/3) d_i (d_k W^k) - Zhat^ij d_j(2 eta/chi^7) - 16 pi sigma^2 eta phi^10 chi^-7 J^i = 0,
//   Zhat^ij d_j(2 eta/chi^7) = (LW)^ij (d_j eta/eta - 7 d_j chi/chi),
//   (LW)^ij = d_i W^j + d_j W^i - (2/3) delta_ij d_k W^k,
//   phi = puncture_phi + chi,  J^i = rho0 h W_L^2 v^i,  v^i = (beta^i + V^i)/alpha,  alpha = eta/phi.
// They plug into core's stencil::vector_residual/vector_relax (vector_sweep.hpp) as the Lower term
// N^i: it reads W only through centred first differences (never W at the point itself), and J
// depends on the fluid, chi, eta and the shift but not on W, so the point Jacobian stays
// -(20/3)/h^2 times the identity.
#include <cstddef>
#include <numbers>

#include "bhnsid/interfaces/spacetime.hpp"
#include "bhnsid/interfaces/vector_sweep.hpp"

namespace bhnsid::momentum {

/// Arrays of one level that the lower-order term reads; the fluid arrays only with matter, the shift
/// only when a shift equation is active (beta = 0 otherwise).
struct Sources {
  const double* chi = nullptr;
  const double* eta = nullptr;
  const double* puncture_phi = nullptr;
  const double* rho0 = nullptr;
  const double* enthalpy = nullptr;
  const double* velocity[3] = {nullptr, nullptr, nullptr};
  const double* shift[3] = {nullptr, nullptr, nullptr};
  std::ptrdiff_t sy = 0, sz = 0;  ///< strides of the level (chi and eta are differenced in place)
  double inv_2h = 0;              ///< 1/(2h) of the level
  double sigma2 = 1;              ///< sigma^2: the matter term of the hatted equation carries it (§1.3)
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

/// N^i = -(LW)^ij (d_j eta/eta - 7 d_j chi/chi) - 16 pi sigma^2 eta phi^10 chi^-7 J^i at one point.
/// Matter = false drops the J term (no fluid); Shift = false reads beta = 0 (no shift equation).
/// The J term counts only where rho0 > 0 (selected, not branched, so that the loop vectorises): a
/// velocity field that is superluminal outside the star (Omega xi grows with radius) gives a NaN
/// there that is never used.
template <bool Matter, bool Shift>
struct MomentumLower {
  Sources s;

  [[gnu::always_inline]] stencil::Triple at(std::ptrdiff_t idx, std::ptrdiff_t i, const stencil::Rows& x, const stencil::Rows& y,
                                            const stencil::Rows& z) const {
    const double h = s.inv_2h;
    const stencil::Triple gx = stencil::gradient(x, i, h), gy = stencil::gradient(y, i, h), gz = stencil::gradient(z, i, h);
    const Sym6 lw = conformal_killing(gx, gy, gz);
    const double* c = s.chi + idx;
    const double* e = s.eta + idx;
    const std::ptrdiff_t sy = s.sy, sz = s.sz;
    const double inv_eta = h / e[0], seven_inv_chi = 7.0 * h / c[0];
    // d_j ln(eta chi^-7) = d_j eta/eta - 7 d_j chi/chi by centred differences of the coefficient fields.
    const double gjx = (e[1] - e[-1]) * inv_eta - (c[1] - c[-1]) * seven_inv_chi;
    const double gjy = (e[sy] - e[-sy]) * inv_eta - (c[sy] - c[-sy]) * seven_inv_chi;
    const double gjz = (e[sz] - e[-sz]) * inv_eta - (c[sz] - c[-sz]) * seven_inv_chi;
    stencil::Triple n{-(lw.xx * gjx + lw.xy * gjy + lw.xz * gjz), -(lw.xy * gjx + lw.yy * gjy + lw.yz * gjz),
                      -(lw.xz * gjx + lw.yz * gjy + lw.zz * gjz)};
    if constexpr (Matter) {
      const double rho0 = s.rho0[idx];
      double ux = s.velocity[0][idx], uy = s.velocity[1][idx], uz = s.velocity[2][idx];
      if constexpr (Shift) {
        ux += s.shift[0][idx];
        uy += s.shift[1][idx];
        uz += s.shift[2][idx];
      }
      const double phi = s.puncture_phi[idx] + c[0];
      const double alpha = e[0] / phi;
      const double lorentz2 = lorentz_squared(phi, e[0], ux, uy, uz);
      const double phi2 = phi * phi, phi4 = phi2 * phi2;
      const double inv_chi = 1.0 / c[0], inv_chi2 = inv_chi * inv_chi;
      // 16 pi sigma^2 eta phi^10 chi^-7, times J^i = rho0 h W^2 u^i / alpha below.
      const double k = 16.0 * std::numbers::pi * s.sigma2 * s.source_scale * e[0] * (phi4 * phi4 * phi2) *
                       (inv_chi2 * inv_chi2 * inv_chi2 * inv_chi);
      const double hh = s.enthalpy[idx];
      const bool in_matter = rho0 > 0;
      n.x -= in_matter ? k * momentum_density(rho0, hh, lorentz2, ux, alpha) : 0.0;
      n.y -= in_matter ? k * momentum_density(rho0, hh, lorentz2, uy, alpha) : 0.0;
      n.z -= in_matter ? k * momentum_density(rho0, hh, lorentz2, uz, alpha) : 0.0;
    }
    return n;
  }
};

}  // namespace bhnsid::momentum
