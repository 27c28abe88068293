#include "evaluator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "box.hpp"

namespace bhnsid::ire {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

int zcount(int a) { return a == 2 ? 1 : 0; }

// A set of points of the box, each with a slot in the compact arrays of the fields stored there.
struct PointSet {
  std::vector<std::int32_t> slot;          // per box point: its slot, -1 where not in the set
  std::vector<std::array<int, 3>> points;  // per slot
  void add(const Box& b, int i, int j, int k) {
    std::int32_t& s = slot[b.at(i, j, k)];
    if (s >= 0) return;
    s = static_cast<std::int32_t>(points.size());
    points.push_back({i, j, k});
  }
};

// Where the residuals are evaluated (every stride-th point with room for the stencils), where the
// derived quantities are needed (those points and their six axis neighbours: inner) and where the
// point fields are needed (inner and its axis neighbours: outer); below z = 0 by mirror images.
struct Needed {
  PointSet inner, outer;
};

bool sampled(const Box& b, int stride, int i, int j, int k) {
  return i % stride == 0 && j % stride == 0 && k % stride == 0 && b.inside(i, j, k, 2);
}

constexpr int kStar[7][3] = {{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

Needed needed_points(const Box& b, int stride) {
  Needed n;
  n.inner.slot.assign(b.size(), -1);
  n.outer.slot.assign(b.size(), -1);
  for (int k = 0; k < b.nz; k += stride)
    for (int j = 0; j < b.ny; j += stride)
      for (int i = 0; i < b.nx; i += stride)
        if (sampled(b, stride, i, j, k))
          for (const auto& o : kStar) n.inner.add(b, i + o[0], j + o[1], std::abs(k + o[2]));
  for (const auto& p : n.inner.points)
    for (const auto& o : kStar) n.outer.add(b, p[0] + o[0], p[1] + o[1], std::abs(p[2] + o[2]));
  return n;
}

// A field on the points of a set; `zero`: filled with zeros (in parallel, which is also where its
// pages are first touched), otherwise left for a fill that writes every value.
Field make_compact(const PointSet& n, int z_indices, bool zero = true) {
  Field f{std::make_unique_for_overwrite<double[]>(n.points.size()), zparity(z_indices), &n.slot};
  if (zero) {
    const auto count = static_cast<std::ptrdiff_t>(n.points.size());
    double* v = f.v.get();
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t q = 0; q < count; ++q) v[q] = 0.0;
  }
  return f;
}

// A finest-level array (no ghosts read) copied onto the points of a set.
Field copy_array(const Grid& grid, const PointSet& set, const double* src, int z_indices) {
  Field f = make_compact(set, z_indices, false);
  const Level& lv = grid.finest();
  const auto count = static_cast<std::ptrdiff_t>(set.points.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t q = 0; q < count; ++q) {
    const auto& p = set.points[static_cast<std::size_t>(q)];
    f.v[static_cast<std::size_t>(q)] = src[lv.at(p[0], p[1], p[2])];
  }
  return f;
}

// One grid component copied onto the points of a set (zero where the grid has no such field).
Field copy(const Grid& grid, const PointSet& set, const char* name, int comp, int z_indices) {
  if (!grid.has_field(name)) return make_compact(set, z_indices);
  return copy_array(grid, set, grid.data(grid.field_id(name), comp, 0), z_indices);
}

// Calls fn(i, j, k) for every point of the set, in parallel.
template <class Fn>
void for_needed(const PointSet& n, Fn&& fn) {
  const auto count = static_cast<std::ptrdiff_t>(n.points.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t q = 0; q < count; ++q) {
    const auto& p = n.points[static_cast<std::size_t>(q)];
    fn(p[0], p[1], p[2]);
  }
}

// The inverse of a symmetric 3x3 matrix given as xx, xy, xz, yy, yz, zz.
std::array<double, 6> inverse(const std::array<double, 6>& g) {
  const double c0 = g[3] * g[5] - g[4] * g[4], c1 = g[2] * g[4] - g[1] * g[5], c2 = g[1] * g[4] - g[2] * g[3];
  const double det = g[0] * c0 + g[1] * c1 + g[2] * c2;
  return {c0 / det, c1 / det, c2 / det, (g[0] * g[5] - g[2] * g[2]) / det, (g[1] * g[2] - g[0] * g[4]) / det,
          (g[0] * g[3] - g[1] * g[1]) / det};
}

// Calls fn(i, j, k) for every point of the box whose stencils reach `margin` points, planes in parallel.
template <class Fn>
void for_points(const Box& b, int margin, Fn&& fn) {
#pragma omp parallel for schedule(static)
  for (int k = 0; k < b.nz; ++k)
    for (int j = 0; j < b.ny; ++j)
      for (int i = 0; i < b.nx; ++i)
        if (b.inside(i, j, k, margin)) fn(i, j, k);
}

struct Geometry {
  Field chi, weight;  // the solution's regular part of phi and the momentum ansatz's weight q, at the outer points
  Field alpha, rho_e, trace_s, first_integral, enthalpy, rho0;
  std::array<Field, 3> beta_up, beta_down, j_up, dalpha;
  std::array<Field, 3> mass_flux;  // rho0 W phi^6 (alpha v^i - B^i) at the outer points (irrotational flow)
  std::array<Field, 6> gamma, k_down, k_up, sigma;
  std::array<std::array<Field, 6>, 3> christoffel;  // [k][pair(i, j)] = Gamma^k_ij
  Field k_trace;
};

std::array<double, 6> metric_at(const Geometry& g, const Box& b, std::size_t p) {
  (void)b;
  return {g.gamma[0].v[p], g.gamma[1].v[p], g.gamma[2].v[p], g.gamma[3].v[p], g.gamma[4].v[p], g.gamma[5].v[p]};
}

// The point values: phi, alpha, beta, gamma = phi^4 delta, the matter (hatted units).
void fill_point_fields(const Grid& grid, const Box& b, const Inputs& in, const Needed& need, Geometry& g, Field& phi) {
  // The metric, lapse and shift are differenced (outer points); the matter only enters at the
  // points where the residuals are evaluated (inner points suffice).
  const PointSet &set = need.outer, &inner = need.inner;
  g.chi = copy(grid, set, fields::chi, 0, 0);
  g.weight = copy(grid, set, fields::ansatz_weight, 0, 0);
  const Field& chi = g.chi;
  for (int a = 0; a < 3; ++a) g.beta_up[static_cast<std::size_t>(a)] = copy(grid, set, fields::shift, a, zcount(a));
  phi = make_compact(set, 0, false);
  // The lapse's alpha as its plugin forms it (refreshed by the caller): which unknown it solves for
  // is its business; the IRE checks the equations alpha must obey.
  g.alpha = copy(grid, set, fields::alpha, 0, 0);
  for (int p = 0; p < 6; ++p) g.gamma[static_cast<std::size_t>(p)] = make_compact(set, (p == 2 || p == 4) ? 1 : 0);
  for (int a = 0; a < 3; ++a) g.beta_down[static_cast<std::size_t>(a)] = make_compact(set, zcount(a), false);
  g.rho0 = copy(grid, inner, fields::rho0, 0, 0);
  // The flow's first integral, whose difference from C_B is the Bernoulli residual.
  g.first_integral = in.first_integral ? copy_array(grid, inner, in.first_integral, 0) : make_compact(inner, 0);
  g.enthalpy = copy(grid, inner, fields::enthalpy, 0, 0);
  // The matter projections are the star's (its kinematics, refreshed from the solution
  // before the evaluation); the IRE checks the field equations they source, not the fluid's motion.
  if (in.fluid) {
    g.rho_e = copy(grid, inner, fields::matter_energy, 0, 0);
    g.trace_s = copy(grid, inner, fields::matter_trace, 0, 0);
    for (int a = 0; a < 3; ++a) g.j_up[static_cast<std::size_t>(a)] = copy(grid, inner, fields::matter_momentum, a, zcount(a));
  } else {
    g.rho_e = make_compact(inner, 0);
    g.trace_s = make_compact(inner, 0);
    for (int a = 0; a < 3; ++a) g.j_up[static_cast<std::size_t>(a)] = make_compact(inner, zcount(a));
  }
  // The rest-mass flux of a flow that solves continuity: its ingredients at the outer points.
  Field rho0_out, lorentz;
  std::array<Field, 3> velocity;
  if (in.lorentz) {
    rho0_out = copy(grid, set, fields::rho0, 0, 0);
    lorentz = copy_array(grid, set, in.lorentz, 0);
    for (int a = 0; a < 3; ++a) {
      velocity[static_cast<std::size_t>(a)] = copy_array(grid, set, in.velocity[a], zcount(a));
      g.mass_flux[static_cast<std::size_t>(a)] = make_compact(set, zcount(a), false);
    }
  }
  for_needed(set, [&](int i, int j, int k) {
    const std::size_t at = b.at(i, j, k);
    const auto p = static_cast<std::size_t>(set.slot[at]);
    double ph = chi.v[p];
    if (in.puncture) {
      const double dx = b.x0 + b.dx * i - in.position[0], dy = b.y0 + b.dx * j - in.position[1],
                   dz = b.z0 + b.dx * k - in.position[2];
      ph += in.bare_mass / (2.0 * std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    phi.v[p] = ph;
    const double psi4 = ph * ph * ph * ph;
    g.gamma[0].v[p] = g.gamma[3].v[p] = g.gamma[5].v[p] = psi4;
    for (int a = 0; a < 3; ++a) g.beta_down[static_cast<std::size_t>(a)].v[p] = psi4 * g.beta_up[static_cast<std::size_t>(a)].v[p];
    if (in.lorentz) {
      // rho0 W phi^6 (alpha v^i - beta^i - Omegahat xi^i), xi = (-y, x, 0) (physics-notes-irrotational §2.1).
      const double xi[3] = {-(b.y0 + b.dx * j), b.x0 + b.dx * i, 0.0};
      const double weight = rho0_out.v[p] > 0 ? rho0_out.v[p] * lorentz.v[p] * psi4 * ph * ph : 0.0;
      for (int a = 0; a < 3; ++a) {
        const auto c = static_cast<std::size_t>(a);
        g.mass_flux[c].v[p] =
            weight * (g.alpha.v[p] * velocity[c].v[p] - g.beta_up[c].v[p] - in.omega_hat * xi[a]);
      }
    }
  });
}

// K_ij = phi^-2 Ahat_ij, Ahat = Bowen-York + Zhat, Zhat^ij = chi^7/(2 q) (LW)^ij with the box's
// own D0 of W (margin 1).
void fill_extrinsic(const Grid& grid, const Box& b, const Inputs& in, const Field& phi, const Needed& need, Geometry& g) {
  const Field& chi = g.chi;
  const Field& weight = g.weight;
  std::array<Field, 3> w;
  for (int a = 0; a < 3; ++a) w[static_cast<std::size_t>(a)] = copy(grid, need.outer, fields::wvec, a, zcount(a));
  for (int a = 0; a < 3; ++a)
    for (int c = a; c < 3; ++c) g.k_down[static_cast<std::size_t>(pair(a, c))] = make_compact(need.inner, zcount(a) + zcount(c), false);
  const bool has_w = grid.has_field(fields::wvec);
  for_needed(need.inner, [&](int i, int j, int k) {
    const auto p = static_cast<std::size_t>(need.outer.slot[b.at(i, j, k)]);
    double dw[3][3] = {};  // dw[a][c] = d_a W^c
    if (has_w)
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) dw[a][c] = d0(b, w[static_cast<std::size_t>(c)], a, i, j, k);
    const double div = dw[0][0] + dw[1][1] + dw[2][2];
    // q > 0 wherever the momentum equation is solved (its plugin checks); without W there is no Zhat.
    const double factor = has_w ? std::pow(chi.v[p], 7) / (2.0 * weight.v[p]) : 0.0;
    double n[3] = {0, 0, 0}, r = 1, pn = 0;
    if (in.puncture) {
      const double d[3] = {b.x0 + b.dx * i - in.position[0], b.y0 + b.dx * j - in.position[1],
                           b.z0 + b.dx * k - in.position[2]};
      r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (int a = 0; a < 3; ++a) n[a] = d[a] / r, pn += in.momentum[static_cast<std::size_t>(a)] * n[a];
    }
    const double inv_phi2 = 1.0 / (phi.v[p] * phi.v[p]);
    for (int a = 0; a < 3; ++a)
      for (int c = a; c < 3; ++c) {
        const double delta = a == c ? 1.0 : 0.0;
        double ahat = factor * (dw[a][c] + dw[c][a] - (2.0 / 3.0) * delta * div);
        if (in.puncture)
          ahat += 1.5 / (r * r) *
                  (in.momentum[static_cast<std::size_t>(a)] * n[c] + in.momentum[static_cast<std::size_t>(c)] * n[a] -
                   (delta - n[a] * n[c]) * pn);
        // Ahat_ij = Ahat^ij (the conformal metric is flat); K_ij = phi^-2 Ahat_ij.
        g.k_down[static_cast<std::size_t>(pair(a, c))].at(b, i, j, k) = inv_phi2 * ahat;
      }
  });
}

// Gamma^k_ij, K^ij, K, d alpha and Sigma_ij (margin 1).
void fill_connection(const Box& b, const Needed& need, Geometry& g) {
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < 3; ++a)
      for (int d = a; d < 3; ++d)
        g.christoffel[static_cast<std::size_t>(c)][static_cast<std::size_t>(pair(a, d))] =
            make_compact(need.inner, zcount(c) + zcount(a) + zcount(d), false);
  for (int a = 0; a < 3; ++a)
    for (int c = a; c < 3; ++c) {
      g.k_up[static_cast<std::size_t>(pair(a, c))] = make_compact(need.inner, zcount(a) + zcount(c), false);
      g.sigma[static_cast<std::size_t>(pair(a, c))] = make_compact(need.inner, zcount(a) + zcount(c), false);
    }
  for (int a = 0; a < 3; ++a) g.dalpha[static_cast<std::size_t>(a)] = make_compact(need.inner, zcount(a), false);
  g.k_trace = make_compact(need.inner, 0, false);
  for_needed(need.inner, [&](int i, int j, int k) {
    const std::size_t at = b.at(i, j, k);
    const auto p = static_cast<std::size_t>(need.outer.slot[at]), q = static_cast<std::size_t>(need.inner.slot[at]);
    const std::array<double, 6> gl = metric_at(g, b, p), gu = inverse(gl);
    double dg[3][6];  // dg[l][pair] = d_l gamma_pair
    for (int l = 0; l < 3; ++l)
      for (int q = 0; q < 6; ++q) dg[l][q] = d0(b, g.gamma[static_cast<std::size_t>(q)], l, i, j, k);
    double gamma[3][3][3];  // Gamma^c_ad
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a)
        for (int d = 0; d < 3; ++d) {
          double s = 0;
          for (int l = 0; l < 3; ++l) s += gu[static_cast<std::size_t>(pair(c, l))] * (dg[a][pair(d, l)] + dg[d][pair(a, l)] - dg[l][pair(a, d)]);
          gamma[c][a][d] = 0.5 * s;
        }
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a)
        for (int d = a; d < 3; ++d) g.christoffel[static_cast<std::size_t>(c)][static_cast<std::size_t>(pair(a, d))].v[q] = gamma[c][a][d];
    double kd[3][3], ku[3][3], trace = 0;
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) kd[a][c] = g.k_down[static_cast<std::size_t>(pair(a, c))].v[q];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        double s = 0;
        for (int e = 0; e < 3; ++e)
          for (int f = 0; f < 3; ++f) s += gu[static_cast<std::size_t>(pair(a, e))] * gu[static_cast<std::size_t>(pair(c, f))] * kd[e][f];
        ku[a][c] = s;
        trace += gu[static_cast<std::size_t>(pair(a, c))] * kd[a][c];
      }
    for (int a = 0; a < 3; ++a)
      for (int c = a; c < 3; ++c) g.k_up[static_cast<std::size_t>(pair(a, c))].v[q] = ku[a][c];
    g.k_trace.v[q] = trace;
    for (int a = 0; a < 3; ++a) g.dalpha[static_cast<std::size_t>(a)].v[q] = d0(b, g.alpha, a, i, j, k);
    // dtg_ij = -2 alpha K_ij + D_i beta_j + D_j beta_i; Sigma = its trace-free part.
    double db[3][3];  // D_a beta_c
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        double s = d0(b, g.beta_down[static_cast<std::size_t>(c)], a, i, j, k);
        for (int e = 0; e < 3; ++e) s -= gamma[e][a][c] * g.beta_down[static_cast<std::size_t>(e)].v[p];
        db[a][c] = s;
      }
    const double al = g.alpha.v[p];
    double dtg[3][3], tr = 0;
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) dtg[a][c] = -2.0 * al * kd[a][c] + db[a][c] + db[c][a];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) tr += gu[static_cast<std::size_t>(pair(a, c))] * dtg[a][c];
    for (int a = 0; a < 3; ++a)
      for (int c = a; c < 3; ++c)
        g.sigma[static_cast<std::size_t>(pair(a, c))].v[q] = dtg[a][c] - gl[static_cast<std::size_t>(pair(a, c))] * tr / 3.0;
  });
}

struct PointResiduals {
  double hamiltonian, momentum[3], lapse, shift[3];
};

// The residuals at a point with margin 2.
PointResiduals residuals_at(const Box& b, const Needed& need, const Geometry& g, double sigma2, int i, int j, int k) {
  const std::size_t at = b.at(i, j, k);
  const auto p = static_cast<std::size_t>(need.outer.slot[at]), q = static_cast<std::size_t>(need.inner.slot[at]);
  const std::array<double, 6> gl = metric_at(g, b, p), gu = inverse(gl);
  auto G = [&](int c, int a, int d) { return g.christoffel[static_cast<std::size_t>(c)][static_cast<std::size_t>(pair(a, d))].v[q]; };
  auto dG = [&](int l, int c, int a, int d) {
    return d0(b, g.christoffel[static_cast<std::size_t>(c)][static_cast<std::size_t>(pair(a, d))], l, i, j, k);
  };
  auto up = [&](int a, int c) { return gu[static_cast<std::size_t>(pair(a, c))]; };
  // R_ad = d_c Gamma^c_ad - d_d Gamma^c_ac + Gamma^c_ce Gamma^e_ad - Gamma^c_de Gamma^e_ac
  double ricci = 0;
  for (int a = 0; a < 3; ++a)
    for (int d = 0; d < 3; ++d) {
      double r = 0;
      for (int c = 0; c < 3; ++c) {
        r += dG(c, c, a, d) - dG(d, c, a, c);
        for (int e = 0; e < 3; ++e) r += G(c, c, e) * G(e, a, d) - G(c, d, e) * G(e, a, c);
      }
      ricci += up(a, d) * r;
    }
  double kk = 0;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      kk += g.k_down[static_cast<std::size_t>(pair(a, c))].v[q] * g.k_up[static_cast<std::size_t>(pair(a, c))].v[q];
  const double trace = g.k_trace.v[q], rho_e = g.rho_e.v[q];
  PointResiduals out{};
  out.hamiltonian = ricci + trace * trace - kk - 16.0 * pi * sigma2 * rho_e;
  double dtrace[3];
  for (int a = 0; a < 3; ++a) dtrace[a] = d0(b, g.k_trace, a, i, j, k);
  for (int a = 0; a < 3; ++a) {
    // D_c K^ac - D^a K - 8 pi sigma^2 j^a
    double s = 0;
    for (int c = 0; c < 3; ++c) {
      s += d0(b, g.k_up[static_cast<std::size_t>(pair(a, c))], c, i, j, k);
      for (int e = 0; e < 3; ++e)
        s += G(a, c, e) * g.k_up[static_cast<std::size_t>(pair(e, c))].v[q] +
             G(c, c, e) * g.k_up[static_cast<std::size_t>(pair(a, e))].v[q];
      s -= up(a, c) * dtrace[c];
    }
    out.momentum[a] = s - 8.0 * pi * sigma2 * g.j_up[static_cast<std::size_t>(a)].v[q];
  }
  // d_t K = -D^2 alpha + alpha (R + K^2 + 4 pi sigma^2 (S - 3 rho_E)) + beta^k d_k K, with the second
  // derivatives of alpha as D0 of D0 alpha (symmetrised).
  double lap_alpha = 0;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      double dd = 0.5 * (d0(b, g.dalpha[static_cast<std::size_t>(c)], a, i, j, k) + d0(b, g.dalpha[static_cast<std::size_t>(a)], c, i, j, k));
      for (int e = 0; e < 3; ++e) dd -= G(e, a, c) * g.dalpha[static_cast<std::size_t>(e)].v[q];
      lap_alpha += up(a, c) * dd;
    }
  double advect = 0;
  for (int a = 0; a < 3; ++a) advect += g.beta_up[static_cast<std::size_t>(a)].v[p] * dtrace[a];
  const double al = g.alpha.v[p];
  out.lapse = -lap_alpha + al * (ricci + trace * trace + 4.0 * pi * sigma2 * (g.trace_s.v[q] - 3.0 * rho_e)) + advect;
  // D^c Sigma_ac = gamma^cd (d_d Sigma_ac - Gamma^e_da Sigma_ec - Gamma^e_dc Sigma_ae)
  auto S = [&](int a, int c) { return g.sigma[static_cast<std::size_t>(pair(a, c))].v[q]; };
  for (int a = 0; a < 3; ++a) {
    double s = 0;
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) {
        double t = d0(b, g.sigma[static_cast<std::size_t>(pair(a, c))], d, i, j, k);
        for (int e = 0; e < 3; ++e) t -= G(e, d, a) * S(e, c) + G(e, d, c) * S(a, e);
        s += up(c, d) * t;
      }
    out.shift[a] = s;
  }
  return out;
}

// The mask widened by w points in the max norm (a cube of side 2w + 1 about every marked point),
// axis by axis; below z = 0 by symmetry.
std::vector<std::uint8_t> dilate(const Box& b, std::vector<std::uint8_t> m, int w) {
  if (w == 0) return m;
  std::vector<std::uint8_t> out(m.size(), 0);
  for (int axis = 0; axis < 3; ++axis) {
    const int len = axis == 0 ? b.nx : axis == 1 ? b.ny : b.nz;
    const int lines_a = axis == 0 ? b.ny : b.nx, lines_b = axis == 2 ? b.ny : b.nz;
#pragma omp parallel
    {
      // A line with its mirror images below z = 0 (z axis, symmetry): index t - lo, t in [lo, len).
      const int lo = axis == 2 && b.mirror ? -(len - 1) : 0;
      std::vector<int> count(static_cast<std::size_t>(len - lo) + 1);
#pragma omp for schedule(static)
      for (int lb = 0; lb < lines_b; ++lb)
        for (int la = 0; la < lines_a; ++la) {
          auto index = [&](int t) {
            const int tt = std::abs(t);
            return axis == 0 ? b.at(tt, la, lb) : axis == 1 ? b.at(la, tt, lb) : b.at(la, lb, tt);
          };
          count[0] = 0;
          for (int t = lo; t < len; ++t) count[static_cast<std::size_t>(t - lo) + 1] = count[static_cast<std::size_t>(t - lo)] + (m[index(t)] ? 1 : 0);
          for (int t = 0; t < len; ++t) {
            const int a0 = std::max(lo, t - w), a1 = std::min(len - 1, t + w);
            out[index(t)] = count[static_cast<std::size_t>(a1 - lo) + 1] > count[static_cast<std::size_t>(a0 - lo)] ? 1 : 0;
          }
        }
    }
    std::swap(m, out);
  }
  return m;
}

// The puncture's region: the bounding box of the excision mask (a cube; without a shift, the cube
// of side max(M/2, 3 dx) about the hole) widened by `exclude_cells` points; below z = 0 by symmetry.
struct PunctureRegion {
  bool any = false;
  int lo[3] = {0, 0, 0}, hi[3] = {-1, -1, -1};
  bool contains(int i, int j, int k) const {
    return any && i >= lo[0] && i <= hi[0] && j >= lo[1] && j <= hi[1] && k >= lo[2] && k <= hi[2];
  }
};

PunctureRegion puncture_region(const Grid& grid, const Box& b, const Inputs& in) {
  PunctureRegion r;
  if (!in.puncture) return r;
  const Level& lv = grid.finest();
  int mask = -1;
  if (grid.has_field(fields::shift)) {
    try {
      mask = grid.mask_id(fields::excision_mask);
    } catch (const std::exception&) {
      mask = -1;  // a shift without a hole has no excision mask
    }
  }
  const double half = 0.5 * std::max(0.5 * in.bare_mass, 3.0 * b.dx) + 1e-12 * b.dx;
  for (int k = 0; k < b.nz; ++k)
    for (int j = 0; j < b.ny; ++j)
      for (int i = 0; i < b.nx; ++i) {
        bool in_core;
        if (mask >= 0) {
          in_core = grid.mask(mask, 0)[lv.at(i, j, k)] != 0;
        } else {
          const double d = std::max({std::fabs(b.x0 + b.dx * i - in.position[0]), std::fabs(b.y0 + b.dx * j - in.position[1]),
                                     std::fabs(b.z0 + b.dx * k - in.position[2])});
          in_core = d <= half;
        }
        if (!in_core) continue;
        const int idx[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) {
          r.lo[a] = r.any ? std::min(r.lo[a], idx[a]) : idx[a];
          r.hi[a] = r.any ? std::max(r.hi[a], idx[a]) : idx[a];
        }
        r.any = true;
      }
  if (b.mirror && r.any && r.lo[2] == 0) r.lo[2] = -r.hi[2];  // the mirror image continues the box
  for (int a = 0; a < 3; ++a) r.lo[a] -= in.exclude_cells, r.hi[a] += in.exclude_cells;
  return r;
}

// Points within `cells` of the star's surface (a rho0 > 0 point next to a rho0 = 0 one), from the
// grid's density at every point.
std::vector<std::uint8_t> surface_band(const Grid& grid, const Box& b, int cells) {
  std::vector<std::uint8_t> edge(b.size(), 0);
  const Level& lv = grid.finest();
  const double* rho0 = grid.data(grid.field_id(fields::rho0), 0, 0);
  auto matter = [&](int i, int j, int k) { return rho0[lv.at(i, j, std::abs(k))] > 0; };
  for_points(b, 1, [&](int i, int j, int k) {
    const bool m = matter(i, j, k);
    if (m != matter(i + 1, j, k) || m != matter(i - 1, j, k) || m != matter(i, j + 1, k) || m != matter(i, j - 1, k) ||
        m != matter(i, j, k + 1) || m != matter(i, j, k - 1))
      edge[b.at(i, j, k)] = 1;
  });
  return dilate(b, std::move(edge), cells);
}

struct Accumulator {
  double sum = 0, max = 0;
  long points = 0;
  void add(const double* r, int n) {
    double s = 0;
    for (int c = 0; c < n; ++c) s += r[c] * r[c], max = std::max(max, std::fabs(r[c]));
    sum += s;
    ++points;
  }
  Norms norms() const { return Norms{points ? std::sqrt(sum / points) : 0.0, max, points}; }
};

std::string number(double v) { return std::isfinite(v) ? fmt::format("{:.10e}", v) : "nan"; }

}  // namespace

Result evaluate(const Grid& grid, const Inputs& in) {
  const Level& lv = grid.finest();
  const Box b(lv);
  const Needed need = needed_points(b, in.stride);
  Geometry g;
  Field phi;
  fill_point_fields(grid, b, in, need, g, phi);
  fill_extrinsic(grid, b, in, phi, need, g);
  fill_connection(b, need, g);
  const PunctureRegion near = puncture_region(grid, b, in);
  const std::vector<std::uint8_t> band = in.fluid ? surface_band(grid, b, in.surface_cells) : std::vector<std::uint8_t>(b.size(), 0);

  const double sigma2 = in.sigma * in.sigma;
  const bool bernoulli = in.fluid && std::isfinite(in.bernoulli) && in.first_integral;
  const bool continuity = in.fluid && in.lorentz;

  Result out;
  out.equations = {"hamiltonian", "momentum", "lapse", "shift"};
  if (bernoulli) out.equations.push_back("bernoulli");
  const std::size_t continuity_at = out.equations.size();
  if (continuity) out.equations.push_back("continuity");
  const std::size_t ne = out.equations.size();
  // Per equation and region (0 away: vacuum; 1 surface; 2 puncture; 3 inside the star away from its
  // surface), accumulated per thread, then summed. Bernoulli and continuity live in the star: their
  // "away" is 3.
  std::vector<std::array<Accumulator, 4>> total(ne);
  const int jaxis = static_cast<int>(std::lround(-b.y0 / b.dx));
  const int kaxis = static_cast<int>(std::lround(-b.z0 / b.dx));
  std::vector<std::string> axis_rows(static_cast<std::size_t>(b.nx));
#pragma omp parallel
  {
    std::vector<std::array<Accumulator, 4>> local(ne);
#pragma omp for schedule(static)
    for (int k = 0; k < b.nz; ++k)
      for (int j = 0; j < b.ny; ++j)
        for (int i = 0; i < b.nx; ++i) {
          if (i % in.stride || j % in.stride || k % in.stride) continue;
          const bool on_axis = j == jaxis && k == kaxis;
          // The stencils need 2 points each way; validate compares resolutions at the coarsest grid's
          // points, so the margin is 2 of its spacings: the same points at every level (a margin of
          // 2 fine points added a shell of 12,000 points at the second level of the paper example).
          if (!b.inside(i, j, k, 2 * in.stride)) {
            if (on_axis) axis_rows[static_cast<std::size_t>(i)] = fmt::format("{:.10g}\tnan\tnan\tnan\tnan\tnan\tnan\tnan\tnan\tnan\tnan\t-\n", b.x0 + b.dx * i);
            continue;
          }
          const std::size_t p = b.at(i, j, k), pi = static_cast<std::size_t>(need.inner.slot[p]);
          const PointResiduals r = residuals_at(b, need, g, sigma2, i, j, k);
          const bool matter = g.rho0.v[pi] > 0;
          const double bern = bernoulli && matter ? g.first_integral.v[pi] - in.bernoulli : nan;
          // The divergence of the rest-mass flux by the IRE's own D0 (the solver's is a cut-cell flux form).
          double mass = nan;
          if (continuity && matter) {
            mass = 0;
            for (int a = 0; a < 3; ++a) mass += d0(b, g.mass_flux[static_cast<std::size_t>(a)], a, i, j, k);
          }
          const int region = near.contains(i, j, k) ? 2 : band[p] ? 1 : matter ? 3 : 0;
          local[0][static_cast<std::size_t>(region)].add(&r.hamiltonian, 1);
          local[1][static_cast<std::size_t>(region)].add(r.momentum, 3);
          local[2][static_cast<std::size_t>(region)].add(&r.lapse, 1);
          local[3][static_cast<std::size_t>(region)].add(r.shift, 3);
          if (bernoulli && matter) local[4][static_cast<std::size_t>(region == 3 ? 0 : region)].add(&bern, 1);
          if (continuity && matter) local[continuity_at][static_cast<std::size_t>(region == 3 ? 0 : region)].add(&mass, 1);
          if (on_axis)
            axis_rows[static_cast<std::size_t>(i)] =
                fmt::format("{:.10g}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\n", b.x0 + b.dx * i, number(r.hamiltonian),
                            number(r.momentum[0]), number(r.momentum[1]), number(r.momentum[2]), number(r.lapse),
                            number(r.shift[0]), number(r.shift[1]), number(r.shift[2]), number(bern), number(mass),
                            region == 2 ? "puncture" : region == 1 ? "surface" : region == 3 ? "star" : "away");
        }
#pragma omp critical
    for (std::size_t e = 0; e < ne; ++e)
      for (int q = 0; q < 4; ++q) {
        Accumulator& t = total[e][static_cast<std::size_t>(q)];
        const Accumulator& l = local[e][static_cast<std::size_t>(q)];
        t.sum += l.sum;
        t.max = std::max(t.max, l.max);
        t.points += l.points;
      }
  }
  for (std::size_t e = 0; e < ne; ++e) {
    out.away[out.equations[e]] = total[e][0].norms();
    out.surface[out.equations[e]] = total[e][1].norms();
    out.puncture[out.equations[e]] = total[e][2].norms();
    out.star[out.equations[e]] = total[e][3].norms();
  }
  out.axis_table =
      "# x\thamiltonian\tmomentum_x\tmomentum_y\tmomentum_z\tlapse\tshift_x\tshift_y\tshift_z\tbernoulli\tcontinuity\tregion\n";
  for (const std::string& row : axis_rows) out.axis_table += row;
  return out;
}

}  // namespace bhnsid::ire
