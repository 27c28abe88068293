#pragma once
// The manufactured problems: exact solutions in closed form and the source terms that make them
// solutions, both analytic (a source obtained by differencing the exact solution would hide the
// truncation error the tests measure). Every operator is written L(u) = lap u + N(u) + s = 0 with s
// the coefficient field "mms_source" (and "mms_source_w" for the coupled partner); README.md lists
// the formulas. Lengths scale with the cube's half-width r_c, so each problem looks the same on
// every grid.
#include <array>
#include <string>

namespace bhnsid::mms {

using Vec3 = std::array<double, 3>;

enum class Problem { poisson, nonlinear, vector, ball, coupled };

Problem problem_from(const std::string& keyword);
const char* to_string(Problem problem);

/// exp(-|x - centre|^2 / width^2) with its Laplacian and gradient, the building block of the
/// smooth solutions.
struct Gaussian {
  Vec3 centre{};
  double width = 1;
  double value(const Vec3& x) const;
  /// lap G = G (4 rho^2 / w^4 - 6 / w^2), rho = |x - centre|.
  double laplacian(const Vec3& x) const;
};

/// The hypre peer's problem (shared/peers/src/problem.hpp) mapped onto the cube: t = (x + r_c) / 2r_c
/// per axis, u = g(tx) g(ty) g(tz), g(t) = t (1 - t) e^t, zero on the faces; s = -lap u.
struct PoissonSolution {
  double half_width = 0.5;
  double u(const Vec3& x) const;
  double source(const Vec3& x) const;
  /// The one-dimensional factors: u = f(x) f(y) f(z), s = -(f''(x) f(y) f(z) + ...), with
  /// f(x) = g(t(x)) and f''(x) = g''(t) / (2 r_c)^2.
  double factor(double x) const;
  double factor_second(double x) const;
};

/// u = 1 + A exp(-|x - p|^2 / w^2) for lap u + c u^5 + s = 0, s = -(lap u + c u^5).
struct NonlinearSolution {
  double half_width = 0.5;
  double c = 0;
  double u(const Vec3& x) const;
  double source(const Vec3& x) const;
  Gaussian bump() const;
  static constexpr double amplitude = 0.5;
};

/// V = grad Phi + Omega (-(y - q_y), x - q_x, 0) G_q: a curl-free and a divergence-free part, V^x
/// and V^y even in z, V^z odd. Operator lap V^i + (1/3) d^i d_j V^j - kappa n^i n_j V^j + s^i with
/// n = x / r_c; s^i = -(4/3 d^i lap Phi + lap V_rot^i - kappa n^i n.V).
struct VectorSolution {
  double half_width = 0.5;
  double kappa = 0;
  Vec3 v(const Vec3& x) const;
  Vec3 source(const Vec3& x) const;
};

/// Newtonian potential of a ball of mass M, radius R at b with the C^1 density
/// rho = rho0 (1 - |x-b|^2/R^2)^2: lap u = 4 pi rho, u = -M/|x - b| outside; s = -4 pi rho.
struct BallSolution {
  Vec3 centre{};
  double mass = 1, radius = 1;
  double rho0() const;
  double density(const Vec3& x) const;
  /// The potential and its radial derivative as functions of r = |x - b|.
  double radial(double r) const;
  double radial_derivative(double r) const;
  double u(const Vec3& x) const;
  double source(const Vec3& x) const;
};

/// The pair lap u + a w + s_u = 0, lap w + b u^3 + s_w = 0 with u = 1 + A_u G_u, w = A_w G_w.
struct CoupledSolution {
  double half_width = 0.5;
  double a = 0, b = 0;
  double u(const Vec3& x) const;
  double w(const Vec3& x) const;
  double source_u(const Vec3& x) const;
  double source_w(const Vec3& x) const;
};

struct ProblemSpec {
  Problem problem = Problem::poisson;
  double half_width = 0.5;
  double nonlinear_c = 0;
  double vector_coupling = 0;
  double ball_mass = 1, ball_radius = 1;
  Vec3 ball_centre{};
  double coupled_a = 0, coupled_b = 0;
};

/// Any problem's exact values and sources, per unknown (0: mms_u or mms_v, 1: the partner mms_w)
/// and component. A switch per call: for setup and analysis, never inside a sweep.
class ExactSolution {
 public:
  explicit ExactSolution(const ProblemSpec& spec);
  Problem problem() const { return spec_.problem; }
  int unknowns() const { return spec_.problem == Problem::coupled ? 2 : 1; }
  int components() const { return spec_.problem == Problem::vector ? 3 : 1; }
  double value(int unknown, int component, const Vec3& x) const;
  double source(int unknown, int component, const Vec3& x) const;
  const ProblemSpec& spec() const { return spec_; }
  const PoissonSolution& poisson() const { return poisson_; }

 private:
  ProblemSpec spec_;
  PoissonSolution poisson_;
  NonlinearSolution nonlinear_;
  VectorSolution vector_;
  BallSolution ball_;
  CoupledSolution coupled_;
};

}  // namespace bhnsid::mms
