#pragma once
// Point functions of the minimal-distortion shift, eq. mindist_hat (physics-notes §2.5; the printed
// d_j phi is the hatted derivative, §1.3):
//   lap beta^i + (1/3) d_i (d_k beta^k)
//     = -(6/phi) [ (d_j beta^i + d_i beta^j) dphi_j - (2/3) dphi_i (d_k beta^k) ]
//       + 2 phi^-6 Ahat^ij d_j alpha + 16 pi sigma^2 alpha phi^4 J^i,
//   phi = Mhat/(2 r) + chi,  dphi_i = -Mhat n_i/(2 r^2) + d_i chi  (the puncture's part analytic),
//   alpha from the "lapse" service (refreshed before each sweep), d_i alpha by centred differences,
//   J^i = j^i, the star's momentum density (refreshed before each sweep).
// The right-hand side enters core's vector sweep (stencil::vector_residual/relax) as the lower-order
// term N = -RHS of L(beta) = lap beta + (1/3) grad div beta + N = 0.
#include <cmath>
#include <cstddef>
#include <numbers>

#include "bhnsid/interfaces/spacetime.hpp"
#include "bhnsid/interfaces/vector_sweep.hpp"

namespace bhnsid::shift {

using stencil::Rows;
using stencil::Triple;

/// Arrays of one level the lower-order term reads, and the constants it needs.
struct Sources {
  const double* chi = nullptr;           ///< regular part of phi (neighbours read: d_i chi)
  const double* alpha = nullptr;         ///< the lapse (neighbours read: d_i alpha)
  double half_mass = 0;            ///< Mhat/2, hole only
  double x0 = 0, y0 = 0, z0 = 0;   ///< the level's point (0, 0, 0) minus xhat_BH, hole only
  double dx = 0;                   ///< the level's spacing
  const double* ahat[6] = {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};  ///< xx, xy, xz, yy, yz, zz (zz unread: traceless)
  MatterSources matter;     ///< j^i and sigma^2 (physics-notes §1.3), matter only
  double source_scale = 1;  ///< TEST ONLY factor on the Ahat term; 1 for physics
  double coupling_scale = 1;  ///< TEST ONLY factor on the (6/phi)(...) d phi term; 1 for physics
  double inv_2h = 0;        ///< 1/(2 dx) of the level: centred first derivatives
  std::ptrdiff_t sy = 0, sz = 0;  ///< the level's strides
};

/// N^i = -RHS^i at one point, for stencil::vector_residual_any / vector_relax_any. Hole: add the
/// puncture's parts of phi and dphi, computed from the point's coordinates (4 arrays fewer to
/// stream than stored ones; the sweep binds the row first, row()). Matter: add the
/// momentum-density term (without the hydro service there is none).
template <bool Hole, bool Matter>
struct ShiftLower {
  Sources s;
  double dy = 0, dz = 0, rho2 = 0;  ///< the bound row's y - yhat_BH, z - zhat_BH, dy^2 + dz^2

  ShiftLower row(int j, int k) const {
    ShiftLower bound = *this;
    if constexpr (Hole) {
      bound.dy = s.y0 + s.dx * j;
      bound.dz = s.z0 + s.dx * k;
      bound.rho2 = bound.dy * bound.dy + bound.dz * bound.dz;
    }
    return bound;
  }

  [[gnu::always_inline]] Triple at(std::ptrdiff_t idx, std::ptrdiff_t i, const Rows& x, const Rows& y, const Rows& z) const {
    const double h = s.inv_2h;
    // d_j beta^i: bx = (d_x beta^x, d_y beta^x, d_z beta^x), and so on.
    const Triple bx = stencil::gradient(x, i, h), by = stencil::gradient(y, i, h), bz = stencil::gradient(z, i, h);
    const double* c = s.chi + idx;
    const double* a = s.alpha + idx;
    const std::ptrdiff_t sy = s.sy, sz = s.sz;
    double phi = c[0];
    double dpx = h * (c[1] - c[-1]), dpy = h * (c[sy] - c[-sy]), dpz = h * (c[sz] - c[-sz]);
    if constexpr (Hole) {
      // Mhat/(2 r) and its gradient -Mhat (x - xhat_BH)/(2 r^3); the puncture is never on a point.
      const double rx = s.x0 + s.dx * i, inv_r = 1.0 / std::sqrt(rx * rx + rho2);
      const double m_r = s.half_mass * inv_r, m_r3 = m_r * inv_r * inv_r;
      phi += m_r;
      dpx -= m_r3 * rx;
      dpy -= m_r3 * dy;
      dpz -= m_r3 * dz;
    }
    const double inv_phi = 1.0 / phi;
    const double alpha = a[0];
    const double dax = h * (a[1] - a[-1]), day = h * (a[sy] - a[-sy]), daz = h * (a[sz] - a[-sz]);

    // (d_j beta^i + d_i beta^j) dphi_j - (2/3) dphi_i div beta
    const double div = bx.x + by.y + bz.z;
    const double sxy = bx.y + by.x, sxz = bx.z + bz.x, syz = by.z + bz.y;
    const double third2 = 2.0 / 3.0;
    const double shear_x = 2.0 * bx.x * dpx + sxy * dpy + sxz * dpz - third2 * dpx * div;
    const double shear_y = sxy * dpx + 2.0 * by.y * dpy + syz * dpz - third2 * dpy * div;
    const double shear_z = sxz * dpx + syz * dpy + 2.0 * bz.z * dpz - third2 * dpz * div;

    // 2 phi^-6 Ahat^ij d_j alpha (times the test-only scale). Ahat is traceless (Bowen-York and
    // Zhat = chi^7/(2 eta) (LW) both are), so Ahat^zz = -Ahat^xx - Ahat^yy, exact up to rounding:
    // one array fewer to stream, and the sweep's cost goes by the arrays it streams (the six
    // components read from one array instead of six made it 21 % faster).
    const double axx = s.ahat[0][idx], axy = s.ahat[1][idx], axz = s.ahat[2][idx], ayy = s.ahat[3][idx],
                 ayz = s.ahat[4][idx], azz = -(axx + ayy);
    const double inv_phi2 = inv_phi * inv_phi;
    const double ka = 2.0 * s.source_scale * inv_phi2 * inv_phi2 * inv_phi2;
    const double six_phi = 6.0 * s.coupling_scale * inv_phi;
    Triple n{six_phi * shear_x - ka * (axx * dax + axy * day + axz * daz),
             six_phi * shear_y - ka * (axy * dax + ayy * day + ayz * daz),
             six_phi * shear_z - ka * (axz * dax + ayz * day + azz * daz)};

    if constexpr (Matter) {
      // 16 pi sigma^2 alpha phi^4 J^i. J depends on beta at the point itself (through v and W), which
      // core's sweep does not allow for in its fixed point Jacobian -(20/3)/h^2: that derivative,
      // 16 pi sigma^2 phi^4 rho0 h W^2 (~ 10 for a neutron star), is tiny next to (20/3)/h^2 (~ 7e3
      // at h = 0.03), and J is refreshed before every sweep, so the converged solution is exact.
      // j^i is 0 outside the matter (the star writes it so).
      const MatterSources& m = s.matter;
      const double phi2 = phi * phi;
      const double k = 16.0 * std::numbers::pi * m.sigma2 * alpha * phi2 * phi2;
      n.x -= k * m.momentum[0][idx];
      n.y -= k * m.momentum[1][idx];
      n.z -= k * m.momentum[2][idx];
    }
    return n;
  }
};

}  // namespace bhnsid::shift
