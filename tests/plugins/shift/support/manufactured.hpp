#pragma once
// The manufactured problem of the shift's convergence test, shared by the TEST_ONLY plugin that
// supplies the fields (test_plugins/fields.cpp) and the unit test that checks it against sympy.
//
// Given smooth chi, eta (phi = chi: no puncture), a traceless symmetric Ahat, sigma and rho0, the
// exact shift beta_exact solves eq. mindist_hat exactly when the momentum density is
//   J^i = [lap beta^i + (1/3) d_i div beta - R0^i] / (16 pi sigma^2 alpha phi^4),
//   R0^i = -(6/phi) [(d_j beta^i + d_i beta^j) dphi_j - (2/3) dphi_i div beta] + 2 phi^-6 Ahat^ij d_j alpha,
// all evaluated at beta_exact. J = rho0 h W^2 U/alpha with U = beta + V: U is parallel to J, and with
// u = phi^2 |U|/alpha (the speed |v|, W^2 = 1/(1 - u^2)) |J| = rho0 h u / (phi^2 (1 - u^2)), a quadratic
// with one root in [0, 1). The fluid velocity is then V = U - beta_exact.
//
// beta_exact is exactly homogeneous of degree -1 about the origin for r >= R (so the Robin rows,
// exact for such fields, add no error of their own) and a C^5 polynomial in r^2 inside:
//   beta^x = 0.03 F1 + 0.02 y F2,  beta^y = -0.025 F1 + 0.025 x F2,  beta^z = 0.02 z F2,
//   F1 = 1/r, F2 = 1/r^2 for r >= R.
// Parities under z -> -z: chi, eta, rho0, beta^x, beta^y, Ahat^xx, yy, zz, xy even; beta^z, Ahat^xz, yz odd.
#include <array>
#include <cmath>
#include <numbers>

namespace bhnsid::shift::test {

constexpr double mms_radius = 1.0;  ///< R
constexpr double mms_sigma = 0.9;

/// f(s), f'(s), f''(s) of a function of s = r^2.
struct Radial {
  double f, df, ddf;
};

/// F1 = 1/r outside R, inside (1/R) p(s/R^2) with the C^5 match p = (693 - 1155 t + 1386 t^2 - 990 t^3
/// + 385 t^4 - 63 t^5)/256.
inline Radial radial_f1(double s) {
  const double R = mms_radius;
  if (s >= R * R) {
    const double r = std::sqrt(s);
    return {1 / r, -0.5 / (s * r), 0.75 / (s * s * r)};
  }
  static constexpr double c[6] = {693 / 256.0, -1155 / 256.0, 1386 / 256.0, -990 / 256.0, 385 / 256.0, -63 / 256.0};
  const double t = s / (R * R);
  double p = 0, dp = 0, ddp = 0, tk = 1;
  for (int k = 0; k < 6; ++k) {
    p += c[k] * tk;
    if (k < 5) dp += (k + 1) * c[k + 1] * tk;
    if (k < 4) ddp += (k + 2) * (k + 1) * c[k + 2] * tk;
    tk *= t;
  }
  return {p / R, dp / (R * R * R), ddp / (R * R * R * R * R)};
}

/// F2 = 1/r^2 outside R, inside (1/R^2) (6 - 15 t + 20 t^2 - 15 t^3 + 6 t^4 - t^5) (C^5).
inline Radial radial_f2(double s) {
  const double R = mms_radius;
  if (s >= R * R) return {1 / s, -1 / (s * s), 2 / (s * s * s)};
  static constexpr double c[6] = {6, -15, 20, -15, 6, -1};
  const double t = s / (R * R);
  double p = 0, dp = 0, ddp = 0, tk = 1;
  for (int k = 0; k < 6; ++k) {
    p += c[k] * tk;
    if (k < 5) dp += (k + 1) * c[k + 1] * tk;
    if (k < 4) ddp += (k + 2) * (k + 1) * c[k + 2] * tk;
    tk *= t;
  }
  const double R2 = R * R;
  return {p / R2, dp / (R2 * R2), ddp / (R2 * R2 * R2)};
}

/// A scalar with its gradient and Hessian at one point.
struct Jet {
  double v = 0;
  double d[3] = {0, 0, 0};
  double dd[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  void add(const Jet& o, double c = 1) {
    v += c * o.v;
    for (int i = 0; i < 3; ++i) {
      d[i] += c * o.d[i];
      for (int j = 0; j < 3; ++j) dd[i][j] += c * o.dd[i][j];
    }
  }
};

/// c x_m F(r^2) (m = -1: c F) with d_i F = 2 F' x_i, d_i d_j F = 4 F'' x_i x_j + 2 F' delta_ij.
inline Jet radial_term(double c, int m, const Radial& F, const std::array<double, 3>& x) {
  Jet t;
  double Fv = F.f, dF[3], ddF[3][3];
  for (int i = 0; i < 3; ++i) {
    dF[i] = 2 * F.df * x[i];
    for (int j = 0; j < 3; ++j) ddF[i][j] = 4 * F.ddf * x[i] * x[j] + (i == j ? 2 * F.df : 0.0);
  }
  const double xm = m < 0 ? 1.0 : x[m];
  t.v = c * xm * Fv;
  for (int i = 0; i < 3; ++i) {
    t.d[i] = c * (xm * dF[i] + (i == m ? Fv : 0.0));
    for (int j = 0; j < 3; ++j)
      t.dd[i][j] = c * (xm * ddF[i][j] + (i == m ? dF[j] : 0.0) + (j == m ? dF[i] : 0.0));
  }
  return t;
}

/// exp(-|x - p|^2 / w^2) with gradient (Hessian not needed).
inline Jet gaussian(const std::array<double, 3>& p, double w, const std::array<double, 3>& x) {
  Jet g;
  double q = 0;
  for (int i = 0; i < 3; ++i) q += (x[i] - p[i]) * (x[i] - p[i]);
  g.v = std::exp(-q / (w * w));
  for (int i = 0; i < 3; ++i) g.d[i] = -2 * (x[i] - p[i]) / (w * w) * g.v;
  return g;
}

/// beta_exact^i with first and second derivatives.
inline std::array<Jet, 3> beta_exact(const std::array<double, 3>& x) {
  const double s = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
  const Radial f1 = radial_f1(s), f2 = radial_f2(s);
  std::array<Jet, 3> b;
  b[0] = radial_term(0.03, -1, f1, x);
  b[0].add(radial_term(0.02, 1, f2, x));
  b[1] = radial_term(-0.025, -1, f1, x);
  b[1].add(radial_term(0.025, 0, f2, x));
  b[2] = radial_term(0.02, 2, f2, x);
  return b;
}

inline Jet chi_exact(const std::array<double, 3>& x) {
  Jet c = gaussian({0.3, -0.2, 0}, 0.8, x);
  Jet one;
  one.v = 1;
  one.add(c, 0.2);
  return one;
}

inline Jet eta_exact(const std::array<double, 3>& x) {
  Jet e;
  e.v = 0.9;
  e.add(gaussian({-0.25, 0.15, 0}, 0.7, x), -0.15);
  return e;
}

/// Ahat^ij stored xx, xy, xz, yy, yz, zz; traceless.
inline std::array<double, 6> ahat_exact(const std::array<double, 3>& x) {
  const double g = gaussian({0.1, 0.2, 0}, 0.7, x).v;
  const double xx = (2.4 + 1.6 * x[0]) * g, yy = (-0.8 + 0.8 * x[1]) * g;
  return {xx, 1.2 * g, 1.6 * x[2] * g, yy, -0.8 * x[2] * g, -(xx + yy)};
}

inline double rho0_exact(const std::array<double, 3>& x) { return 0.1 + 0.1 * gaussian({0.2, 0.1, 0}, 0.6, x).v; }

/// The momentum density J^i for which beta_exact solves the equation (the formula at the top).
inline std::array<double, 3> required_current(const std::array<double, 3>& x) {
  const std::array<Jet, 3> b = beta_exact(x);
  const Jet chi = chi_exact(x), eta = eta_exact(x);
  const std::array<double, 6> a = ahat_exact(x);
  const double A[3][3] = {{a[0], a[1], a[2]}, {a[1], a[3], a[4]}, {a[2], a[4], a[5]}};
  const double phi = chi.v, alpha = eta.v / phi;
  double dalpha[3];
  for (int j = 0; j < 3; ++j) dalpha[j] = (eta.d[j] - alpha * chi.d[j]) / phi;
  const double div = b[0].d[0] + b[1].d[1] + b[2].d[2];
  std::array<double, 3> J{};
  for (int i = 0; i < 3; ++i) {
    double principal = 0, grad_div = 0, shear = 0, adal = 0;
    for (int j = 0; j < 3; ++j) {
      principal += b[i].dd[j][j];
      grad_div += b[j].dd[j][i];
      shear += (b[i].d[j] + b[j].d[i]) * chi.d[j];
      adal += A[i][j] * dalpha[j];
    }
    shear -= 2.0 / 3.0 * chi.d[i] * div;
    const double r0 = -6 / phi * shear + 2 * std::pow(phi, -6) * adal;
    J[static_cast<std::size_t>(i)] =
        (principal + grad_div / 3 - r0) / (16 * std::numbers::pi * mms_sigma * mms_sigma * alpha * std::pow(phi, 4));
  }
  return J;
}

/// rho0, P = rho0^2, h = 1 + 2 rho0 (Gamma = 2, k = 1) and the fluid velocity V that give J = required_current
/// at beta = beta_exact.
struct FluidPoint {
  double rho0, press, enthalpy;
  std::array<double, 3> velocity;
};

inline FluidPoint fluid_exact(const std::array<double, 3>& x) {
  FluidPoint f;
  f.rho0 = rho0_exact(x);
  f.press = f.rho0 * f.rho0;
  f.enthalpy = 1 + 2 * f.rho0;
  const std::array<double, 3> J = required_current(x);
  const std::array<Jet, 3> b = beta_exact(x);
  const double phi = chi_exact(x).v, alpha = eta_exact(x).v / phi;
  const double jn = std::sqrt(J[0] * J[0] + J[1] * J[1] + J[2] * J[2]);
  const double a = jn * phi * phi / (f.rho0 * f.enthalpy);
  const double u = 2 * a / (1 + std::sqrt(1 + 4 * a * a));  // u / (1 - u^2) = a
  const double un = alpha * u / (phi * phi);                // |U|
  for (int i = 0; i < 3; ++i)
    f.velocity[static_cast<std::size_t>(i)] = (jn > 0 ? un * J[static_cast<std::size_t>(i)] / jn : 0.0) - b[i].v;
  return f;
}

}  // namespace bhnsid::shift::test
