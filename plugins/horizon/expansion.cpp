#include "expansion.hpp"

#include <cmath>
#include <numbers>

#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::horizon {

SurfaceTables::SurfaceTables(const SurfaceBasis& b) : basis(b), modes(b.modes().size()) {
  const auto& pts = b.points();
  y.resize(pts.size() * modes);
  // theta derivatives by 5-point differences (error ~ 1e-9 l^5 at this step, round-off ~ 1e-10);
  // phi derivatives exactly.
  const double e = 1e-3;
  for (std::size_t p = 0; p < pts.size(); ++p)
    for (std::size_t m = 0; m < modes; ++m) {
      const Mode& mode = b.modes()[m];
      const double th = pts[p].theta, ph = pts[p].phi;
      auto f = [&](double t, double q) { return real_harmonic(mode, t, q); };
      const double f0 = f(th, ph), fp1 = f(th + e, ph), fm1 = f(th - e, ph), fp2 = f(th + 2 * e, ph), fm2 = f(th - 2 * e, ph);
      const double dt = (8 * (fp1 - fm1) - (fp2 - fm2)) / (12 * e);
      const double dtt = (16 * (fp1 + fm1) - (fp2 + fm2) - 30 * f0) / (12 * e * e);
      // d/dphi of cos(m phi) is -m sin(m phi) = -m Y_{l,-m}-shape; done through the shifted angle.
      const double m_abs = std::abs(mode.m), shift = mode.m == 0 ? 0.0 : std::numbers::pi / (2 * m_abs);
      const double dphi = mode.m == 0 ? 0.0 : m_abs * f(th, ph + shift);
      const double dphiphi = -m_abs * m_abs * f0;
      auto g = [&](double t) { return mode.m == 0 ? 0.0 : m_abs * f(t, ph + shift); };
      const double dtphi = mode.m == 0 ? 0.0 : (8 * (g(th + e) - g(th - e)) - (g(th + 2 * e) - g(th - 2 * e))) / (12 * e);
      y[p * modes + m] = {f0, dt, dphi, dtt, dtphi, dphiphi};
    }
}

SurfaceGeometry geometry(const SurfaceTables& t, const std::vector<double>& a, std::size_t point,
                         const std::array<double, 3>& centre) {
  double h = 0, ht = 0, hp = 0, htt = 0, htp = 0, hpp = 0;
  for (std::size_t m = 0; m < t.modes; ++m) {
    const auto& y = t.at(point, m);
    h += a[m] * y[0], ht += a[m] * y[1], hp += a[m] * y[2];
    htt += a[m] * y[3], htp += a[m] * y[4], hpp += a[m] * y[5];
  }
  const SurfacePoint& sp = t.basis.points()[point];
  const double st = std::sin(sp.theta), ct = std::cos(sp.theta), sf = std::sin(sp.phi), cf = std::cos(sp.phi);
  SurfaceGeometry g;
  g.h = h;
  const double n[3] = {st * cf, st * sf, ct};
  for (int i = 0; i < 3; ++i) g.x[static_cast<std::size_t>(i)] = centre[static_cast<std::size_t>(i)] + h * n[i];
  // At the point (r = h): d_i theta = e_theta_i / r, d_i phi = e_phi_i / (r sin theta).
  const double r = h, rho = r * st;
  const double et[3] = {ct * cf, ct * sf, -st}, ep[3] = {-sf, cf, 0.0};
  double dth[3], dph[3];
  for (int i = 0; i < 3; ++i) dth[i] = et[i] / r, dph[i] = ep[i] / rho;
  // Second Cartesian derivatives of theta and phi (x = r n): from theta = atan2(rho, z), phi = atan2(y, x).
  const double x = r * n[0], yv = r * n[1], z = r * n[2], r2 = r * r, rho2 = rho * rho;
  double ddth[3][3], ddph[3][3];
  {
    // d theta/dx_i = (x_i z / rho, ..., -rho) / r^2 with x_i in the plane; differentiate once more.
    const double r4 = r2 * r2;
    const double xi[2] = {x, yv};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        const double delta = i == j ? 1.0 : 0.0;
        ddth[i][j] = z * (delta / (rho * r2) - xi[i] * xi[j] / (rho * rho2 * r2) - 2 * xi[i] * xi[j] / (rho * r4));
      }
    for (int i = 0; i < 2; ++i) {
      ddth[i][2] = ddth[2][i] = xi[i] / (rho * r2) - 2 * xi[i] * z * z / (rho * r4);
    }
    ddth[2][2] = 2 * rho * z / r4;
    ddph[0][0] = 2 * x * yv / (rho2 * rho2);
    ddph[1][1] = -2 * x * yv / (rho2 * rho2);
    ddph[0][1] = ddph[1][0] = (yv * yv - x * x) / (rho2 * rho2);
    ddph[0][2] = ddph[2][0] = ddph[1][2] = ddph[2][1] = ddph[2][2] = 0;
  }
  // F = r - h: grad F = n - grad h, Hessian = (delta - n n)/r - Hess h.
  double grad[3], hess[3][3];
  for (int i = 0; i < 3; ++i) grad[i] = n[i] - (ht * dth[i] + hp * dph[i]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double hh = htt * dth[i] * dth[j] + htp * (dth[i] * dph[j] + dph[i] * dth[j]) + hpp * dph[i] * dph[j] +
                        ht * ddth[i][j] + hp * ddph[i][j];
      hess[i][j] = ((i == j ? 1.0 : 0.0) - n[i] * n[j]) / r - hh;
    }
  const double norm = std::sqrt(grad[0] * grad[0] + grad[1] * grad[1] + grad[2] * grad[2]);
  double laplace = 0, nn = 0;
  for (int i = 0; i < 3; ++i) {
    g.normal[static_cast<std::size_t>(i)] = grad[i] / norm;
    laplace += hess[i][i];
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) nn += g.normal[static_cast<std::size_t>(i)] * g.normal[static_cast<std::size_t>(j)] * hess[i][j];
  g.divergence = (laplace - nn) / norm;
  // dA = h sqrt(h^2 + h_theta^2 + h_phi^2/sin^2 theta) d(cos theta) d phi.
  g.area = h * std::sqrt(h * h + ht * ht + hp * hp / (st * st)) * sp.weight;
  return g;
}

double scaled_expansion(const SurfaceGeometry& g, const FieldPoint& f) {
  const auto& s = g.normal;
  double ss = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      ss += f.ahat[static_cast<std::size_t>(sym_index(i, j))] * s[static_cast<std::size_t>(i)] * s[static_cast<std::size_t>(j)];
  const double phi2 = f.phi * f.phi;
  return g.divergence + 4 * (s[0] * f.dlnphi[0] + s[1] * f.dlnphi[1] + s[2] * f.dlnphi[2]) + ss / (phi2 * phi2);
}

}  // namespace bhnsid::horizon
