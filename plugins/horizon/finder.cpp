#include "finder.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "bhnsid/interfaces/spacetime.hpp"
#include "expansion.hpp"

namespace bhnsid::horizon {

namespace {

/// phi^2 Theta at every collocation point; false when a point leaves the sampled box or is not finite.
bool residual(const LocalFields& f, const SurfaceTables& t, const std::vector<double>& a, Eigen::VectorXd& out,
              std::string& why) {
  const auto& centre = f.hole().position;
  const std::size_t n = t.basis.points().size();
  out.resize(static_cast<Eigen::Index>(n));
  for (std::size_t p = 0; p < n; ++p) {
    const SurfaceGeometry g = geometry(t, a, p, centre);
    if (!(g.h > 0) || !f.covers(g.x)) {
      why = fmt::format("the surface reached r = {:.4g} (hatted) at theta = {:.3f}, phi = {:.3f}, outside the "
                        "region sampled about the puncture",
                        g.h, t.basis.points()[p].theta, t.basis.points()[p].phi);
      return false;
    }
    const double v = scaled_expansion(g, f.at(g.x));
    if (!std::isfinite(v)) {
      why = fmt::format("the expansion is {} at r = {:.4g}", v, g.h);
      return false;
    }
    out(static_cast<Eigen::Index>(p)) = v;
  }
  return true;
}

}  // namespace

Horizon find_horizon(const LocalFields& f, const SurfaceBasis& basis, const FinderSettings& s) {
  Horizon out;
  const SurfaceTables tables(basis);
  const std::size_t modes = basis.modes().size();
  const double r0 = s.initial_radius > 0 ? s.initial_radius : 0.5 * f.hole().mass;
  std::vector<double> a = s.start.size() == modes ? s.start : basis.sphere(r0);
  Eigen::VectorXd r, shifted;
  Eigen::MatrixXd jac;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr;
  const double y00 = 1.0 / std::sqrt(4 * std::numbers::pi);
  std::string why;
  // A chord method: the Jacobian (a residual per coefficient) is kept while the steps shrink fast,
  // and rebuilt when they do not; a search from the last horizon then costs one Jacobian.
  bool fresh = false;
  double last_step = HUGE_VAL;
  for (out.iterations = 1; out.iterations <= s.max_iterations; ++out.iterations) {
    if (!residual(f, tables, a, r, why)) {
      out.failure = why;
      return out;
    }
    const double mean = a[0] * y00;
    if (!fresh) {
      jac.resize(r.size(), static_cast<Eigen::Index>(modes));
      const double eps = 1e-7 * mean;
      for (std::size_t m = 0; m < modes; ++m) {
        std::vector<double> b = a;
        b[m] += eps;
        if (!residual(f, tables, b, shifted, why)) {
          out.failure = why;
          return out;
        }
        jac.col(static_cast<Eigen::Index>(m)) = (shifted - r) / eps;
      }
      qr.compute(jac);
      fresh = true;
    }
    Eigen::VectorXd step = qr.solve(-r);
    // A step larger than a fifth of the radius is shortened: the expansion is far from linear there.
    const double largest = step.cwiseAbs().maxCoeff() * y00 * std::sqrt(static_cast<double>(modes));
    if (largest > 0.2 * mean) step *= 0.2 * mean / largest;
    for (std::size_t m = 0; m < modes; ++m) a[m] += step(static_cast<Eigen::Index>(m));
    out.residual = r.cwiseAbs().maxCoeff() * mean;
    if (!std::isfinite(step.squaredNorm())) {
      out.failure = "the Newton step is not finite";
      return out;
    }
    const double size = step.cwiseAbs().maxCoeff() * y00;
    if (size <= s.tolerance * mean) {
      out.found = true;
      break;
    }
    if (size > 0.1 * last_step) fresh = false;  // slower than a tenfold decrease: a new Jacobian
    last_step = size;
  }
  if (!out.found) {
    out.failure = fmt::format("not converged in horizon.max_iterations = {} Newton steps (last max |phi^2 Theta| r = {:.3e})",
                              s.max_iterations, out.residual);
    return out;
  }
  if (!residual(f, tables, a, r, why)) {
    out.found = false;
    out.failure = why;
    return out;
  }
  out.residual = r.cwiseAbs().maxCoeff() * a[0] * y00;
  out.coefficients = a;
  // Area, radii and spin by the collocation points' quadrature.
  const auto& centre = f.hole().position;
  double area = 0, flat = 0, radius_sum = 0, spin = 0;
  out.radius_min = 1e300;
  out.radius_max = 0;
  for (std::size_t p = 0; p < basis.points().size(); ++p) {
    const SurfaceGeometry g = geometry(tables, a, p, centre);
    const FieldPoint fp = f.at(g.x);
    const double phi2 = fp.phi * fp.phi;
    area += phi2 * phi2 * g.area;
    flat += g.area;
    radius_sum += g.h * basis.points()[p].weight;
    out.radius_min = std::min(out.radius_min, g.h);
    out.radius_max = std::max(out.radius_max, g.h);
    // Ahat_ij phi^i s^j with phi = (-(y - y_BH), x - x_BH, 0).
    const double rot[3] = {-(g.x[1] - centre[1]), g.x[0] - centre[0], 0.0};
    double k = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) k += fp.ahat[static_cast<std::size_t>(sym_index(i, j))] * rot[i] * g.normal[static_cast<std::size_t>(j)];
    spin += k * g.area;
  }
  (void)flat;
  out.area_hat = area;
  out.radius_mean = radius_sum / (4 * std::numbers::pi);
  out.spin_hat = spin / (8 * std::numbers::pi);
  // The l = 1 part, d_i = (3/4 pi) sum h n_i dOmega, for h = h0 + d.n + (l >= 2).
  std::array<double, 3> d{};
  for (std::size_t p = 0; p < basis.points().size(); ++p) {
    const SurfacePoint& sp = basis.points()[p];
    const double h = basis.radius(a, sp.theta, sp.phi);
    const double n[3] = {std::sin(sp.theta) * std::cos(sp.phi), std::sin(sp.theta) * std::sin(sp.phi), std::cos(sp.theta)};
    for (int i = 0; i < 3; ++i) d[static_cast<std::size_t>(i)] += 3.0 / (4 * std::numbers::pi) * sp.weight * h * n[i];
  }
  out.offset = d;
  return out;
}

}  // namespace bhnsid::horizon
