#pragma once
// The manufactured solution of the momentum plugin's convergence test: a smooth W_exact (Gaussians
// times linear polynomials, W^x and W^y even in z, W^z odd), analytic chi, eta and puncture_phi, and
// the momentum density J^i that makes W_exact an exact continuum solution of eq. mom_ansatz_hat
//   lap W^i + (1/3) d_i (d_k W^k) - (LW)^ij (d_j eta/eta - 7 d_j chi/chi) = 16 pi sigma^2 eta phi^10 chi^-7 J^i.
// Every derivative is in closed form (value, gradient and Hessian of each Gaussian term), so the
// source carries no discretisation error of its own; test_momentum_mms.cpp checks them against
// fourth-order differences. Header-only: used by the test plugin (mms/momentum_mms.cpp) and the
// unit tests. Lengths are absolute, made for the cube r_c = 1.92 of the tests: every Gaussian of W
// is below 1e-8 (with its radial derivative) on the faces, so W_exact meets the Robin condition
// W + x.grad W = 0 to that level and the faces add nothing to the error.
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace bhnsid::momentum::test {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<Vec3, 3>;

/// A function with its gradient and Hessian at one point.
struct Jet {
  double value = 0;
  Vec3 grad{};
  Mat3 hess{};
  Jet& operator+=(const Jet& o) {
    value += o.value;
    for (int i = 0; i < 3; ++i) {
      grad[i] += o.grad[i];
      for (int j = 0; j < 3; ++j) hess[i][j] += o.hess[i][j];
    }
    return *this;
  }
};

/// amp (b + a.(x - c)) exp(-|x - c|^2 / w^2):
///   d_i f = amp [a_i G + p d_i G],  d_i d_j f = amp [a_i d_j G + a_j d_i G + p d_i d_j G],
///   p = b + a.d,  d = x - c,  d_i G = -2 d_i G / w^2,  d_i d_j G = (4 d_i d_j / w^4 - 2 delta_ij / w^2) G.
struct GaussPoly {
  double amp = 0, b = 1;
  Vec3 a{}, c{};
  double w = 1;

  Jet at(const Vec3& x) const {
    const Vec3 d{x[0] - c[0], x[1] - c[1], x[2] - c[2]};
    const double w2 = w * w;
    const double g = std::exp(-(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / w2);
    const double p = b + a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
    Vec3 dg{};
    for (int i = 0; i < 3; ++i) dg[i] = -2.0 * d[i] / w2 * g;
    Jet out;
    out.value = amp * p * g;
    for (int i = 0; i < 3; ++i) {
      out.grad[i] = amp * (a[i] * g + p * dg[i]);
      for (int j = 0; j < 3; ++j) {
        const double ddg = (4.0 * d[i] * d[j] / (w2 * w2) - (i == j ? 2.0 / w2 : 0.0)) * g;
        out.hess[i][j] = amp * (a[i] * dg[j] + a[j] * dg[i] + p * ddg);
      }
    }
    return out;
  }
};

struct Problem {
  /// W^a = the sum of its terms; centres on z = 0, so W^x, W^y (a_z = 0) are even in z and W^z
  /// (b = 0, a = (0, 0, a_z)) is odd.
  std::vector<GaussPoly> w[3] = {
      {{0.6, 1.0, {1.2, 0.8, 0.0}, {0.15, -0.1, 0.0}, 0.36}},
      {{0.5, 1.0, {-0.9, 0.5, 0.0}, {-0.2, 0.1, 0.0}, 0.34}, {-0.3, 1.0, {0.0, 0.0, 0.0}, {0.1, 0.25, 0.0}, 0.3}},
      {{0.8, 0.0, {0.0, 0.0, 2.0}, {0.05, 0.15, 0.0}, 0.36}},
  };
  GaussPoly chi_bump{0.3, 1.0, {0.0, 0.0, 0.0}, {0.1, 0.2, 0.0}, 0.5};     ///< chi = 1 + this
  GaussPoly eta_bump{-0.25, 1.0, {0.0, 0.0, 0.0}, {-0.15, 0.0, 0.0}, 0.55};  ///< eta = 1 + this
  double puncture_phi = 0.1;  ///< a constant stand-in, so that phi = puncture_phi + chi differs from chi
  double sigma = 0.8;

  Jet component(int a, const Vec3& x) const {
    Jet j;
    for (const GaussPoly& t : w[a]) j += t.at(x);
    return j;
  }
  Vec3 exact(const Vec3& x) const { return {component(0, x).value, component(1, x).value, component(2, x).value}; }
  Jet chi(const Vec3& x) const {
    Jet j = chi_bump.at(x);
    j.value += 1.0;
    return j;
  }
  Jet eta(const Vec3& x) const {
    Jet j = eta_bump.at(x);
    j.value += 1.0;
    return j;
  }

  /// lap W^i + (1/3) d_i div W - (LW)^ij (d_j eta/eta - 7 d_j chi/chi) of W_exact.
  Vec3 operator_of_exact(const Vec3& x) const {
    const Jet wj[3] = {component(0, x), component(1, x), component(2, x)};
    const Jet c = chi(x), e = eta(x);
    double div = 0;
    for (int k = 0; k < 3; ++k) div += wj[k].grad[k];
    Vec3 g{};
    for (int j = 0; j < 3; ++j) g[j] = e.grad[j] / e.value - 7.0 * c.grad[j] / c.value;
    Vec3 out{};
    for (int i = 0; i < 3; ++i) {
      double lap = 0, grad_div = 0, lower = 0;
      for (int j = 0; j < 3; ++j) {
        lap += wj[i].hess[j][j];
        grad_div += wj[j].hess[i][j];
        const double lw = wj[j].grad[i] + wj[i].grad[j] - (i == j ? 2.0 / 3.0 * div : 0.0);
        lower += lw * g[j];
      }
      out[i] = lap + grad_div / 3.0 - lower;
    }
    return out;
  }

  /// 16 pi sigma^2 eta phi^10 chi^-7 at x.
  double source_factor(const Vec3& x) const {
    const double c = chi(x).value, e = eta(x).value, phi = puncture_phi + c;
    return 16.0 * std::numbers::pi * sigma * sigma * e * std::pow(phi, 10) / std::pow(c, 7);
  }

  /// The momentum density J^i for which W_exact solves the equation.
  Vec3 momentum_density(const Vec3& x) const {
    const Vec3 s = operator_of_exact(x);
    const double f = source_factor(x);
    return {s[0] / f, s[1] / f, s[2] / f};
  }

  /// The fluid that carries J with h = 1, P = 0, beta = 0: coordinate velocity V = scale J and, from
  /// J = rho0 W_L^2 V / alpha with W_L^2 = 1/(1 - v2), v2 = phi^6 |V|^2 / eta^2,
  /// rho0 = alpha (1 - v2) / scale. Needs v2 < 1.
  struct Fluid {
    double rho0 = 0, v2 = 0;
    Vec3 velocity{};
  };
  Fluid fluid(const Vec3& x, double scale) const {
    const Vec3 j = momentum_density(x);
    const double c = chi(x).value, e = eta(x).value, phi = puncture_phi + c;
    Fluid f;
    for (int i = 0; i < 3; ++i) f.velocity[i] = scale * j[i];
    const double v = f.velocity[0] * f.velocity[0] + f.velocity[1] * f.velocity[1] + f.velocity[2] * f.velocity[2];
    f.v2 = std::pow(phi, 6) * v / (e * e);
    f.rho0 = (e / phi) * (1.0 - f.v2) / scale;
    return f;
  }
};

}  // namespace bhnsid::momentum::test
