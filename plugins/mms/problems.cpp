#include "problems.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace bhnsid::mms {

namespace {

double dist2(const Vec3& x, const Vec3& c) {
  const double dx = x[0] - c[0], dy = x[1] - c[1], dz = x[2] - c[2];
  return dx * dx + dy * dy + dz * dz;
}

Vec3 scaled(double s, const Vec3& v) { return {s * v[0], s * v[1], s * v[2]}; }

// The peer's one-dimensional factor and its second derivative on [0, 1].
double g(double t) { return t * (1 - t) * std::exp(t); }
double g2(double t) { return -t * (t + 3) * std::exp(t); }

// Shapes of the smooth solutions in units of r_c. Centres lie on the plane z = 0 so that every
// solution has the parity equatorial symmetry asks for; they sit off the origin and off each other
// so that no accidental symmetry hides a wrong term.
constexpr Vec3 nonlinear_centre{0.1, -0.05, 0.0};
constexpr double nonlinear_width = 0.5;

constexpr double potential_amplitude = 0.3;  // Phi = A r_c G_p, so |grad Phi| = O(1)
constexpr Vec3 potential_centre{0.15, -0.1, 0.0};
constexpr double potential_width = 0.5;
constexpr Vec3 rotation_centre{-0.1, 0.2, 0.0};  // Omega = 1 / r_c, so |V_rot| = O(1)
constexpr double rotation_width = 0.6;

constexpr double coupled_u_amplitude = 0.4;
constexpr Vec3 coupled_u_centre{0.2, 0.15, 0.0};
constexpr double coupled_u_width = 0.5;
constexpr double coupled_w_amplitude = 0.6;
constexpr Vec3 coupled_w_centre{-0.1, -0.2, 0.0};
constexpr double coupled_w_width = 0.4;

}  // namespace

Problem problem_from(const std::string& keyword) {
  if (keyword == "poisson") return Problem::poisson;
  if (keyword == "nonlinear") return Problem::nonlinear;
  if (keyword == "vector") return Problem::vector;
  if (keyword == "ball") return Problem::ball;
  if (keyword == "coupled") return Problem::coupled;
  throw std::logic_error("mms: unknown problem keyword '" + keyword + "'");
}

const char* to_string(Problem problem) {
  switch (problem) {
    case Problem::poisson: return "poisson";
    case Problem::nonlinear: return "nonlinear";
    case Problem::vector: return "vector";
    case Problem::ball: return "ball";
    case Problem::coupled: return "coupled";
  }
  return "?";
}

double Gaussian::value(const Vec3& x) const { return std::exp(-dist2(x, centre) / (width * width)); }

double Gaussian::laplacian(const Vec3& x) const {
  const double w2 = width * width;
  return value(x) * (4 * dist2(x, centre) / (w2 * w2) - 6 / w2);
}

// ---- poisson

double PoissonSolution::factor(double x) const { return g((x + half_width) / (2 * half_width)); }

// d^2/dx^2 = (1/L^2) d^2/dt^2 with L = 2 r_c.
double PoissonSolution::factor_second(double x) const {
  const double L = 2 * half_width;
  return g2((x + half_width) / L) / (L * L);
}

double PoissonSolution::u(const Vec3& x) const { return factor(x[0]) * factor(x[1]) * factor(x[2]); }

double PoissonSolution::source(const Vec3& x) const {
  const double fx = factor(x[0]), fy = factor(x[1]), fz = factor(x[2]);
  return -(factor_second(x[0]) * fy * fz + fx * factor_second(x[1]) * fz + fx * fy * factor_second(x[2]));
}

// ---- nonlinear

Gaussian NonlinearSolution::bump() const {
  return Gaussian{scaled(half_width, nonlinear_centre), nonlinear_width * half_width};
}

double NonlinearSolution::u(const Vec3& x) const { return 1 + amplitude * bump().value(x); }

double NonlinearSolution::source(const Vec3& x) const {
  const double v = u(x), v2 = v * v;
  return -(amplitude * bump().laplacian(x) + c * v2 * v2 * v);
}

// ---- vector

namespace {

struct VectorParts {
  Vec3 v, lap, grad_div;  // V, lap V, d^i d_j V^j
};

VectorParts vector_parts(double rc, const Vec3& x) {
  VectorParts out{};
  // Curl-free part V = grad Phi: lap V = grad lap Phi = grad div V, so lap V^i + (1/3) d^i div V
  // is (4/3) d^i lap Phi; d^i lap Phi = Phi d_i (20/w^4 - 8 rho^2/w^6) for a Gaussian Phi.
  const Gaussian gp{scaled(rc, potential_centre), potential_width * rc};
  const double phi = potential_amplitude * rc * gp.value(x);
  const double wp2 = gp.width * gp.width, rho2 = dist2(x, gp.centre);
  const double grad_lap = phi * (20 / (wp2 * wp2) - 8 * rho2 / (wp2 * wp2 * wp2));
  // Divergence-free part V = Omega (-e_y, e_x, 0) G_q, e = x - q: each component is a linear
  // function vanishing at q times G_q, so lap V^i = V^i (4 rho^2/w^4 - 10/w^2), div V = 0.
  const Gaussian gq{scaled(rc, rotation_centre), rotation_width * rc};
  const double omega_g = gq.value(x) / rc;
  const double wq2 = gq.width * gq.width, rq2 = dist2(x, gq.centre);
  const double rot_factor = 4 * rq2 / (wq2 * wq2) - 10 / wq2;
  const Vec3 rot{-omega_g * (x[1] - gq.centre[1]), omega_g * (x[0] - gq.centre[0]), 0.0};
  for (std::size_t a = 0; a < 3; ++a) {
    const double d = x[a] - gp.centre[a];
    out.v[a] = -2 * d * phi / wp2 + rot[a];
    out.lap[a] = d * grad_lap + rot[a] * rot_factor;
    out.grad_div[a] = d * grad_lap;
  }
  return out;
}

}  // namespace

Vec3 VectorSolution::v(const Vec3& x) const { return vector_parts(half_width, x).v; }

Vec3 VectorSolution::source(const Vec3& x) const {
  const VectorParts p = vector_parts(half_width, x);
  const Vec3 n = scaled(1 / half_width, x);
  const double n_dot_v = n[0] * p.v[0] + n[1] * p.v[1] + n[2] * p.v[2];
  Vec3 s;
  for (std::size_t i = 0; i < 3; ++i) s[i] = -(p.lap[i] + p.grad_div[i] / 3 - kappa * n[i] * n_dot_v);
  return s;
}

// ---- ball

// M = 4 pi rho0 int_0^R r^2 (1 - r^2/R^2)^2 dr = 4 pi rho0 R^3 (1/3 - 2/5 + 1/7) = 32 pi rho0 R^3 / 105.
double BallSolution::rho0() const { return 105 * mass / (32 * std::numbers::pi * radius * radius * radius); }

double BallSolution::density(const Vec3& x) const {
  const double xi2 = dist2(x, centre) / (radius * radius);
  return xi2 < 1 ? rho0() * (1 - xi2) * (1 - xi2) : 0.0;
}

// Inside, (r^2 u')' = 4 pi rho r^2 integrated from a regular centre gives
// u' = 4 pi rho0 (r/3 - 2r^3/5R^2 + r^5/7R^4), which is M/R^2 at R; the constant makes u = -M/R
// there. With xi = r/R: u = M/(16R) (-35 + 35 xi^2 - 21 xi^4 + 5 xi^6).
double BallSolution::radial(double r) const {
  if (r >= radius) return -mass / r;
  const double xi2 = (r / radius) * (r / radius);
  return mass / (16 * radius) * (-35 + xi2 * (35 + xi2 * (-21 + 5 * xi2)));
}

double BallSolution::radial_derivative(double r) const {
  if (r >= radius) return mass / (r * r);
  const double xi = r / radius, xi2 = xi * xi;
  return mass / (16 * radius * radius) * xi * (70 + xi2 * (-84 + 30 * xi2));
}

double BallSolution::u(const Vec3& x) const { return radial(std::sqrt(dist2(x, centre))); }

double BallSolution::source(const Vec3& x) const { return -4 * std::numbers::pi * density(x); }

// ---- coupled

namespace {
Gaussian coupled_u_bump(double rc) { return {scaled(rc, coupled_u_centre), coupled_u_width * rc}; }
Gaussian coupled_w_bump(double rc) { return {scaled(rc, coupled_w_centre), coupled_w_width * rc}; }
}  // namespace

double CoupledSolution::u(const Vec3& x) const { return 1 + coupled_u_amplitude * coupled_u_bump(half_width).value(x); }

double CoupledSolution::w(const Vec3& x) const { return coupled_w_amplitude * coupled_w_bump(half_width).value(x); }

double CoupledSolution::source_u(const Vec3& x) const {
  return -(coupled_u_amplitude * coupled_u_bump(half_width).laplacian(x) + a * w(x));
}

double CoupledSolution::source_w(const Vec3& x) const {
  const double v = u(x);
  return -(coupled_w_amplitude * coupled_w_bump(half_width).laplacian(x) + b * v * v * v);
}

// ---- any problem

ExactSolution::ExactSolution(const ProblemSpec& spec) : spec_(spec) {
  poisson_.half_width = spec.half_width;
  nonlinear_.half_width = spec.half_width;
  nonlinear_.c = spec.nonlinear_c;
  vector_.half_width = spec.half_width;
  vector_.kappa = spec.vector_coupling;
  ball_.centre = spec.ball_centre;
  ball_.mass = spec.ball_mass;
  ball_.radius = spec.ball_radius;
  coupled_.half_width = spec.half_width;
  coupled_.a = spec.coupled_a;
  coupled_.b = spec.coupled_b;
}

double ExactSolution::value(int unknown, int component, const Vec3& x) const {
  switch (spec_.problem) {
    case Problem::poisson: return poisson_.u(x);
    case Problem::nonlinear: return nonlinear_.u(x);
    case Problem::vector: return vector_.v(x)[static_cast<std::size_t>(component)];
    case Problem::ball: return ball_.u(x);
    case Problem::coupled: return unknown == 0 ? coupled_.u(x) : coupled_.w(x);
  }
  return 0;
}

double ExactSolution::source(int unknown, int component, const Vec3& x) const {
  switch (spec_.problem) {
    case Problem::poisson: return poisson_.source(x);
    case Problem::nonlinear: return nonlinear_.source(x);
    case Problem::vector: return vector_.source(x)[static_cast<std::size_t>(component)];
    case Problem::ball: return ball_.source(x);
    case Problem::coupled: return unknown == 0 ? coupled_.source_u(x) : coupled_.source_w(x);
  }
  return 0;
}

}  // namespace bhnsid::mms
