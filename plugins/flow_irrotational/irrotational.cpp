#include "irrotational.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "corotating_start.hpp"

namespace bhnsid::flow_irrotational {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// dhat Psitilde at an interior stored point of a level. `solved` null: centred differences through
/// whatever the neighbours hold (the extension outside the star). Otherwise only neighbours the
/// potential was solved at and extended from are read (one-sided next to the surface, 0 with
/// neither): the stencil of the velocities a user reads. Psitilde is even in z, so d_z vanishes on
/// the plane z = 0.
std::array<double, 3> gradient(const Level& lv, const double* psi, const std::uint8_t* solved, int i, int j, int k) {
  std::array<double, 3> g{0.0, 0.0, 0.0};
  if (i < 1 || i > lv.nx - 2 || j < 1 || j > lv.ny - 2 || k > lv.nz - 2 || (k < 1 && !lv.z_symmetry)) return g;
  const std::ptrdiff_t p = lv.at(i, j, k);
  const std::ptrdiff_t step[3] = {1, lv.sy, lv.sz};
  for (int d = 0; d < 3; ++d) {
    if (d == 2 && k == 0 && lv.z_symmetry) continue;
    const std::ptrdiff_t up = p + step[d], down = p - step[d];
    if (!solved) {
      g[d] = (psi[up] - psi[down]) / (2 * lv.dx);
      continue;
    }
    const bool u = solved[up] != 0, w = solved[down] != 0;
    g[d] = u && w ? (psi[up] - psi[down]) / (2 * lv.dx) : u ? (psi[up] - psi[p]) / lv.dx : w ? (psi[p] - psi[down]) / lv.dx : 0.0;
  }
  return g;
}

/// The finest-level arrays the flow reads, ghosts filled: alpha, phi, beta (null without a shift).
struct Fields {
  std::vector<double> alpha, phi, beta[3];
  bool has_shift = false;
};

Fields finest_fields(Grid& grid, const Lapse& lapse) {
  const Level& lv = grid.finest();
  Fields f;
  const double* a = lapse_on(grid, lapse, 0);
  f.alpha.assign(a, a + lv.size);
  grid.fill_ghosts(f.alpha.data(), Parity{}, 0);
  const double* chi = grid.data(grid.field_id(fields::chi), 0, 0);
  const double* pphi = grid.data(grid.field_id(fields::puncture_phi), 0, 0);
  f.phi.assign(lv.size, 1.0);
  for (std::size_t p = 0; p < lv.size; ++p) f.phi[p] = pphi[p] + chi[p];
  grid.fill_ghosts(f.phi.data(), Parity{}, 0);
  f.has_shift = grid.has_field(fields::shift);
  for (int c = 0; c < 3; ++c) {
    f.beta[c].assign(lv.size, 0.0);
    if (!f.has_shift) continue;
    const double* b = grid.data(grid.field_id(fields::shift), c, 0);
    std::copy(b, b + lv.size, f.beta[c].begin());
    grid.fill_ghosts(f.beta[c].data(), Parity{c == 2 ? -1 : 1, 1}, 0);
  }
  return f;
}

/// G = sqrt(((1 + B.dPsitilde)/alpha)^2 - phi^-4 |dPsitilde|^2), NaN where it is not real and positive.
double first_integral_g(double alpha, double phi, const double b[3], const std::array<double, 3>& g) {
  const double l = (1.0 + b[0] * g[0] + b[1] * g[1] + b[2] * g[2]) / alpha;
  const double phi2 = phi * phi;
  const double g2 = l * l - (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]) / (phi2 * phi2);
  return alpha > 0 && l > 0 && g2 > 0 ? std::sqrt(g2) : nan;
}

/// Calls fn(i, j, k, p) for every stored point of a level, OpenMP over planes (the gradients need
/// the indices, so for_stored_points_xy does not serve).
template <class Fn>
void for_each_point(const Level& lv, Fn&& fn) {
#pragma omp parallel for schedule(static)
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) fn(i, j, k, lv.at(i, j, k));
}

/// The arrays of one level the flow reads; beta null without a shift equation.
struct LevelFields {
  const double *rho0, *press, *enthalpy, *chi, *puncture_phi, *psi;
  const double* beta[3] = {nullptr, nullptr, nullptr};
  double phi(std::ptrdiff_t p) const { return puncture_phi[p] + chi[p]; }
};

LevelFields level_fields(Grid& grid, int psi, int level) {
  LevelFields f{grid.data(grid.field_id(fields::rho0), 0, level),  grid.data(grid.field_id(fields::press), 0, level),
                grid.data(grid.field_id(fields::enthalpy), 0, level), grid.data(grid.field_id(fields::chi), 0, level),
                grid.data(grid.field_id(fields::puncture_phi), 0, level), grid.data(psi, 0, level)};
  if (grid.has_field(fields::shift))
    for (int a = 0; a < 3; ++a) f.beta[a] = grid.data(grid.field_id(fields::shift), a, level);
  return f;
}

/// B = s beta + Omegahat xi at stored point (i, j) of a level (s = shift_scale, 1 but in the reset).
std::array<double, 3> frame_shift(const Level& lv, const LevelFields& f, double omega_hat, std::ptrdiff_t p, int i, int j,
                                  double shift_scale = 1.0) {
  std::array<double, 3> b{-omega_hat * lv.y(j), omega_hat * lv.x(i), 0.0};
  for (int a = 0; a < 3; ++a) b[static_cast<std::size_t>(a)] += f.beta[a] ? shift_scale * f.beta[a][p] : 0.0;
  return b;
}

/// W = sqrt(1 + phi^-4 |p|^2/h^2), p = C_B dhat Psitilde.
double lorentz(const std::array<double, 3>& g, double phi, double h, double bernoulli) {
  const double phi2 = phi * phi, p2 = bernoulli * bernoulli * (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  return std::sqrt(1.0 + p2 / (phi2 * phi2 * h * h));
}

}  // namespace

void Irrotational::attach(Grid& grid, const Lapse& lapse, const Eos& eos) {
  lapse_ = &lapse;
  eos_ = &eos;
  psi_ = grid.add_field(potential_field, {core::TensorKind::scalar});
}

const Lapse& Irrotational::lapse() const {
  if (!lapse_) throw core::RunFailure("flow_irrotational: used before SETUP gave it the lapse");
  return *lapse_;
}

bool Irrotational::corotating(Grid& grid) const {
  if (!decided_) {
    decided_ = true;
    const Level& lv = grid.finest();
    const double* psi = grid.data(psi_, 0, 0);
    corotating_ = corotating_start_ > 0 && std::all_of(psi, psi + lv.size, [](double v) { return v == 0.0; });
  }
  return corotating_;
}

double Irrotational::prepare(Grid& grid, const FlowConstants& c) {
  ++prepared_;
  if (corotating(grid) && prepared_ <= corotating_start_) return 1.0;  // not settled: no potential yet
  // The first solve after a corotating start replaces a flow that carried the whole velocity: taken
  // in part, it would halve the star's momentum at one stroke.
  relaxation_ = corotating_ ? 1.0 : settings_.relaxation;
  corotating_ = false;
  const Level& lv = grid.finest();
  const Fields f = finest_fields(grid, lapse());
  const double* rho0 = grid.data(grid.field_id(fields::rho0), 0, 0);
  double* psi = grid.data(psi_, 0, 0);
  // The star's box, widened by the band the level set and the extension need.
  constexpr int margin = 4;
  std::array<std::array<int, 2>, 3> box{{{lv.nx, -1}, {lv.ny, -1}, {lv.nz, -1}}};
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i)
        if (rho0[lv.at(i, j, k)] > 0) {
          const int v[3] = {i, j, k};
          for (int a = 0; a < 3; ++a) box[a] = {std::min(box[a][0], v[a]), std::max(box[a][1], v[a])};
        }
  if (box[0][1] < 0) throw core::RunFailure("flow_irrotational: no matter on the grid to solve the velocity potential in");
  const int extent[3] = {lv.nx, lv.ny, lv.nz};
  for (int a = 0; a < 3; ++a)
    box[a] = {std::max(box[a][0] - margin, a == 2 && lv.z_symmetry ? 0 : 1), std::min(box[a][1] + margin, extent[a] - 2)};
  // The level set s = htilde - 1, htilde = C_B G from the current fields and Psitilde, in a band of
  // three points about the star (elsewhere -1: no second star about the hole, where alpha < C_B).
  std::vector<double> level_set(lv.size, -1.0);
  for (int k = box[2][0]; k <= box[2][1]; ++k)
    for (int j = box[1][0]; j <= box[1][1]; ++j)
      for (int i = box[0][0]; i <= box[0][1]; ++i) {
        bool near = false;
        for (int dk = -3; dk <= 3 && !near; ++dk)
          for (int dj = -3; dj <= 3 && !near; ++dj)
            for (int di = -3; di <= 3 && !near; ++di) {
              const int kk = lv.z_symmetry ? std::abs(k + dk) : k + dk;
              if (i + di < 0 || i + di >= lv.nx || j + dj < 0 || j + dj >= lv.ny || kk < 0 || kk >= lv.nz) continue;
              near = rho0[lv.at(i + di, j + dj, kk)] > 0;
            }
        if (!near) continue;
        const std::ptrdiff_t p = lv.at(i, j, k);
        // The star's own level set: the enthalpy its last reset placed the matter by (the first
        // integral with the modelled fields); before the first reset, the first integral now.
        if (reset_enthalpy_.size() == lv.size) {
          if (reset_enthalpy_[p] > 0) level_set[p] = reset_enthalpy_[p] - 1.0;
          continue;
        }
        const double b[3] = {f.beta[0][p] - c.omega_hat * lv.y(j), f.beta[1][p] + c.omega_hat * lv.x(i), f.beta[2][p]};
        const double g = first_integral_g(f.alpha[p], f.phi[p], b, gradient(lv, psi, nullptr, i, j, k));
        if (std::isfinite(g)) level_set[p] = c.bernoulli * g - 1.0;
      }
  grid.fill_ghosts(level_set.data(), Parity{}, 0);
  PotentialCoefficients coefficients;
  coefficients.alpha = f.alpha.data();
  coefficients.phi = f.phi.data();
  for (int a = 0; a < 3; ++a) coefficients.beta[a] = f.has_shift ? f.beta[a].data() : nullptr;
  coefficients.level_set = level_set.data();
  coefficients.omega_hat = c.omega_hat;
  coefficients.box = box;
  if (held_system_.size() == lv.size) {
    coefficients.held_system = held_system_.data();
    coefficients.held_source = held_source_.data();
  }
  // The gauge vertex: the density maximum's axis point.
  double best = -1;
  for (int i = box[0][0]; i <= box[0][1]; ++i) {
    const double r = rho0[lv.at(i, lv.n / 2, 0)];
    if (r > best) best = r, coefficients.centre = {lv.x(i), 0.0, 0.0};
  }
  if (psi_xi_.size() != lv.size) psi_xi_.assign(lv.size, 0.0);
  // How much the solve moves Psitilde in the star, relative to its size there.
  std::vector<double> before(lv.size);
  std::copy(psi, psi + lv.size, before.begin());
  last_ = solve_potential(grid, psi_, psi_xi_.data(), *eos_, coefficients, settings_);
  psi_omega_ = c.omega_hat;
  if (!last_.converged)
    throw core::RunFailure(fmt::format("flow_irrotational: the velocity potential's solve did not converge ({} unknowns, "
                                       "{} iterations, relative residual {:.3e} against {:.1e})",
                                       last_.unknowns, last_.iterations, last_.residual, settings_.tolerance));
  // Under-relaxed: the potential drives the star's momentum, the momentum the shift, and the shift
  // the potential's source B = beta + Omegahat xi, in which it cancels about half of the rotation
  // at the star, a loop with a gain near -1 that one V-cycle per outer step damps only just.
  if (relaxation_ < 1) {
    for (std::size_t p = 0; p < lv.size; ++p) psi[p] = before[p] + relaxation_ * (psi[p] - before[p]);
    grid.fill_ghosts(psi_, 0);
  }
  double change = 0, size = 0;
  for (std::size_t p = 0; p < lv.size; ++p)
    if (level_set[p] > 0) {
      change = std::max(change, std::fabs(psi[p] - before[p]));
      size = std::max(size, std::fabs(psi[p]));
    }
  change = size > 0 ? change / size : change;
  // Once the star has settled, a vertex that has been in the system (or among the extension's
  // sources) stays there. The vertex on the surface otherwise enters and leaves with each reset, and
  // with it the tangential stencils and the extension's start: a map with jumps, about which the
  // outer iteration cycled (period 2 to 12, star change 1e-5 to 1e-4) instead of converging.
  source_ = last_.source;
  if (change < settle_change) {
    held_system_ = last_.system;
    held_source_ = last_.source;
  }
  return change;
}

void Irrotational::set_constants(Grid& grid, const FlowConstants& c) {
  // The potential's rotation part follows the Newton step's Omegahat at once (the shift's part waits
  // for the next field solve), so that the reset and the next field solve see the flow that step
  // chose: a first step from Kepler's Omega (60 % high with the paper's lapse) otherwise leaves the
  // next field solve a momentum, and a shift, that cancel most of B at the star, and the next Newton
  // step no lever arm.
  const Level& lv = grid.finest();
  if (psi_xi_.size() != lv.size || c.omega_hat == psi_omega_) return;
  double* psi = grid.data(psi_, 0, 0);
  // An under-relaxed solve took that fraction of its Omegahat-dependence too.
  const double change = relaxation_ * (c.omega_hat - psi_omega_);
  for (std::size_t p = 0; p < lv.size; ++p) psi[p] += change * psi_xi_[p];
  grid.fill_ghosts(psi_, 0);
  psi_omega_ = c.omega_hat;
}

void Irrotational::update_sources(Grid& grid, int level, const FlowConstants& c) const {
  const Level& lv = grid.level(level);
  const LevelFields f = level_fields(grid, psi_, level);
  double* energy = grid.data(grid.field_id(fields::matter_energy), 0, level);
  double* trace = grid.data(grid.field_id(fields::matter_trace), 0, level);
  const int mom = grid.field_id(fields::matter_momentum);
  double* j_up[3] = {grid.data(mom, 0, level), grid.data(mom, 1, level), grid.data(mom, 2, level)};
  if (corotating(grid)) {
    // rho_E = rho0 h W^2 - P, S = rho0 h (W^2 - 1) + 3 P, j^i = rho0 h W^2 U^i / alpha.
    const double* alpha = lapse_on(grid, lapse(), level);
    for_each_point(lv, [&](int i, int j, int, std::ptrdiff_t p) {
      const std::array<double, 3> u = frame_shift(lv, f, c.omega_hat, p, i, j);
      const double d = corotating_start::frame_norm(alpha[p], f.phi(p), u.data());
      if (!(f.rho0[p] > 0) || !std::isfinite(d)) {
        energy[p] = trace[p] = j_up[0][p] = j_up[1][p] = j_up[2][p] = 0.0;
        return;
      }
      const double w2 = alpha[p] * alpha[p] / d, rho_h = f.rho0[p] * f.enthalpy[p];
      energy[p] = rho_h * w2 - f.press[p];
      trace[p] = rho_h * (w2 - 1.0) + 3.0 * f.press[p];
      for (int a = 0; a < 3; ++a) j_up[a][p] = rho_h * w2 * u[static_cast<std::size_t>(a)] / alpha[p];
    });
    return;
  }
  for_each_point(lv, [&](int i, int j, int k, std::ptrdiff_t p) {
    if (!(f.rho0[p] > 0)) {
      energy[p] = trace[p] = j_up[0][p] = j_up[1][p] = j_up[2][p] = 0.0;
      return;
    }
    const std::array<double, 3> g = gradient(lv, f.psi, nullptr, i, j, k);
    const double phi = f.phi(p), phi2 = phi * phi, h = f.enthalpy[p];
    const double w = lorentz(g, phi, h, c.bernoulli), rho_h = f.rho0[p] * h;
    energy[p] = rho_h * w * w - f.press[p];
    trace[p] = rho_h * (w * w - 1.0) + 3.0 * f.press[p];
    for (int a = 0; a < 3; ++a) j_up[a][p] = f.rho0[p] * w / (phi2 * phi2) * c.bernoulli * g[static_cast<std::size_t>(a)];
  });
}

void Irrotational::velocity(Grid& grid, const FlowConstants& c, double* lorentz_out, double* const* v) const {
  const Level& lv = grid.finest();
  const LevelFields f = level_fields(grid, psi_, 0);
  if (corotating(grid)) {
    // W = alpha/sqrt(D), v^i = U^i/alpha; W NaN where matter cannot corotate.
    const double* alpha = lapse_on(grid, lapse(), 0);
    for_each_point(lv, [&](int i, int j, int, std::ptrdiff_t p) {
      const bool matter = f.rho0[p] > 0;
      const std::array<double, 3> u = frame_shift(lv, f, c.omega_hat, p, i, j);
      const double d = corotating_start::frame_norm(alpha[p], f.phi(p), u.data());
      lorentz_out[p] = matter ? alpha[p] / std::sqrt(d) : 1.0;
      if (v)
        for (int a = 0; a < 3; ++a) v[a][p] = matter ? u[static_cast<std::size_t>(a)] / alpha[p] : 0.0;
    });
    return;
  }
  for_each_point(lv, [&](int i, int j, int k, std::ptrdiff_t p) {
    if (!(f.rho0[p] > 0)) {
      lorentz_out[p] = 1.0;
      if (v)
        for (int a = 0; a < 3; ++a) v[a][p] = 0.0;
      return;
    }
    // Stencils through the extension's sources only: the velocity in the last matter layer reads no
    // extended value.
    const std::array<double, 3> g = gradient(lv, f.psi, solved_mask(lv), i, j, k);
    const double phi = f.phi(p), phi2 = phi * phi, h = f.enthalpy[p];
    const double w = lorentz(g, phi, h, c.bernoulli);
    lorentz_out[p] = w;
    if (v)
      for (int a = 0; a < 3; ++a) v[a][p] = c.bernoulli * g[static_cast<std::size_t>(a)] / (phi2 * phi2 * h * w);
  });
}

void Irrotational::enthalpy(Grid& grid, const FlowConstants& c, const double* alpha, const double* phi, double* h) const {
  const Level& lv = grid.finest();
  const LevelFields f = level_fields(grid, psi_, 0);
  const bool corotation = corotating(grid);
  // The reset places the matter by the Newton step's model of the flow: the shift scaled with
  // Omegahat as axis_residual scales it (the potential follows in set_constants). With the shift as
  // the last field solve left it, the reset's star and the Newton step's disagree by the shift's
  // change, and where the star's own momentum drags the frame (beta^y about -0.55 Omegahat xhat at
  // the centre of a mu_bn = 10 star) the outer iteration swung with period 2 (Omegahat 0.26 <-> 0.33).
  const double shift_scale = corotation || !(axis_omega_ > 0) ? 1.0 : c.omega_hat / axis_omega_;
  for_each_point(lv, [&](int i, int j, int k, std::ptrdiff_t p) {
    const std::array<double, 3> b = frame_shift(lv, f, c.omega_hat, p, i, j, shift_scale);
    if (corotation) {
      h[p] = corotating_start::enthalpy(alpha[p], phi[p], b.data(), c.bernoulli);
      return;
    }
    const double g = first_integral_g(alpha[p], phi[p], b.data(), gradient(lv, f.psi, nullptr, i, j, k));
    h[p] = std::isfinite(g) ? c.bernoulli * g : -1.0;
  });
  reset_enthalpy_.assign(h, h + lv.size);
}

void Irrotational::first_integral(Grid& grid, const FlowConstants& c, double* out) const {
  const Level& lv = grid.finest();
  const LevelFields f = level_fields(grid, psi_, 0);
  const double* alpha = lapse_on(grid, lapse(), 0);
  const bool corotation = corotating(grid);
  for_each_point(lv, [&](int i, int j, int k, std::ptrdiff_t p) {
    if (!(f.rho0[p] > 0)) {
      out[p] = nan;
      return;
    }
    if (corotation) {  // h/u^t = h sqrt(D)
      const std::array<double, 3> u = frame_shift(lv, f, c.omega_hat, p, i, j);
      out[p] = f.enthalpy[p] * std::sqrt(corotating_start::frame_norm(alpha[p], f.phi(p), u.data()));
      return;
    }
    const std::array<double, 3> g = gradient(lv, f.psi, solved_mask(lv), i, j, k);
    const double h = f.enthalpy[p], w = lorentz(g, f.phi(p), h, c.bernoulli);
    const std::array<double, 3> b = frame_shift(lv, f, c.omega_hat, p, i, j);
    // h alpha W - B^i p_i with p = C_B dhat Psitilde.
    out[p] = h * alpha[p] * w - c.bernoulli * (b[0] * g[0] + b[1] * g[1] + b[2] * g[2]);
  });
}

const std::uint8_t* Irrotational::solved_mask(const Level& lv) const {
  return source_.size() == lv.size ? source_.data() : nullptr;
}

std::array<double, 3> Irrotational::potential_size(Grid& grid) const {
  const Level& lv = grid.finest();
  const double* rho0 = grid.data(grid.field_id(fields::rho0), 0, 0);
  const double* psi = grid.data(psi_, 0, 0);
  double psi_max = 0, grad_max = 0, weighted = 0, mass = 0;
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const std::ptrdiff_t p = lv.at(i, j, k);
        if (!(rho0[p] > 0)) continue;
        psi_max = std::max(psi_max, std::fabs(psi[p]));
        // The plane z = 0 stands for half a layer of the mirrored grid.
        const double weight = rho0[p] * (lv.z_symmetry && k == 0 ? 0.5 : 1.0);
        weighted += weight * psi[p] * psi[p];
        mass += weight;
        const std::array<double, 3> g = gradient(lv, psi, solved_mask(lv), i, j, k);
        grad_max = std::max(grad_max, std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]));
      }
  mass = grid.global_sum(mass);
  return {grid.global_max(psi_max), grid.global_max(grad_max), mass > 0 ? std::sqrt(grid.global_sum(weighted) / mass) : 0.0};
}

namespace {

/// dhat_y of `psi` at (x, 0, 0) from the axis points within four spacings on the star's side of it
/// (`inward` > 0: larger x, < 0: smaller, 0: both), at least half a spacing away: their centred
/// differences, fitted by a least-squares quadratic in x (a line with two points, the value with
/// one). The surface points xhat = 1 and xhat_A sit where a centred stencil would read the extension
/// outside the star; and a choice of points by the star's level set would change with the vertex
/// that lies on the surface, which enters and leaves the star from one step to the next. These
/// points are fixed for the run (xhat = 1 and xhat_A are).
double axis_dy(const Level& lv, const double* psi, double x, int inward) {
  const int j0 = lv.n / 2;
  std::vector<double> xs, ds;
  for (int i = 1; i < lv.nx - 1; ++i) {
    const double d = lv.x(i) - x;
    if (std::fabs(d) > 4 * lv.dx || (inward != 0 && d * inward < 0.5 * lv.dx)) continue;
    const std::ptrdiff_t up = lv.at(i, j0 + 1, 0), down = lv.at(i, j0 - 1, 0);
    xs.push_back(d);
    ds.push_back((psi[up] - psi[down]) / (2 * lv.dx));
  }
  const std::size_t n = xs.size();
  if (n == 0) return 0.0;
  if (n == 1) return ds[0];
  // Normal equations of d(x) = c0 + c1 x (+ c2 x^2), x relative to the point: d(point) = c0.
  const int m = n >= 3 ? 3 : 2;
  double a[3][3] = {}, r[3] = {};
  for (std::size_t q = 0; q < n; ++q) {
    const double basis[3] = {1.0, xs[q], xs[q] * xs[q]};
    for (int u = 0; u < m; ++u) {
      r[u] += basis[u] * ds[q];
      for (int v = 0; v < m; ++v) a[u][v] += basis[u] * basis[v];
    }
  }
  // Gaussian elimination on the small symmetric system.
  for (int c = 0; c < m; ++c)
    for (int row = c + 1; row < m; ++row) {
      const double f = a[row][c] / a[c][c];
      for (int v = c; v < m; ++v) a[row][v] -= f * a[c][v];
      r[row] -= f * r[c];
    }
  double sol[3] = {};
  for (int c = m - 1; c >= 0; --c) {
    double t = r[c];
    for (int v = c + 1; v < m; ++v) t -= a[c][v] * sol[v];
    sol[c] = t / a[c][c];
  }
  return sol[0];
}

}  // namespace

void Irrotational::freeze_axis(Grid& grid, const std::vector<double>& xs, const FlowConstants& c) {
  const Level& lv = grid.finest();
  const double* psi = grid.data(psi_, 0, 0);
  axis_x_ = xs;
  axis_p_.assign(xs.size(), 0.0);
  axis_beta_y_.assign(xs.size(), 0.0);
  const double* beta_y = grid.has_field(fields::shift) ? grid.data(grid.field_id(fields::shift), 1, 0) : nullptr;
  // The star's side of each point: towards the one of them with the most matter (the centre).
  const double* rho0 = grid.data(grid.field_id(fields::rho0), 0, 0);
  double centre = xs.empty() ? 0.0 : xs[0], densest = -1;
  for (const double x : xs) {
    const double r = grid.interpolate(rho0, Parity{}, 0, {x, 0, 0});
    if (r > densest) densest = r, centre = x;
  }
  for (std::size_t p = 0; p < xs.size(); ++p) {
    const int inward = xs[p] == centre ? 0 : xs[p] < centre ? 1 : -1;
    axis_p_[p] = axis_dy(lv, psi, xs[p], inward);
    if (beta_y) axis_beta_y_[p] = grid.interpolate(beta_y, Parity{}, 0, {xs[p], 0, 0});
  }
  axis_omega_ = c.omega_hat;
  corotating(grid);
}

AxisResidual Irrotational::axis_residual(std::size_t p, double alpha, double phi, double omega_hat, double bernoulli,
                                         double enthalpy) const {
  // F_P = C^2 G_P^2 - h_P^2, G^2 = (1 + u q)^2/alpha^2 - q^2/phi^4, with the potential's gradient
  // q = dhat_y Psitilde and u = beta^y + xhat Omegahat both scaled with Omegahat: the potential is
  // driven by B = beta + Omegahat xi, and beta by the star's momentum, which the potential carries
  // (near the orbit the shift cancels about half of Omegahat xi at the star, so a model with beta
  // frozen overshoots by two and the outer iteration oscillates). With q frozen, the Newton step
  // maps Omega to Omega*^2/Omega and never converges.
  const double x = axis_x_.at(p), w0 = axis_omega_;
  if (corotating_) {
    double r[3];
    corotating_start::axis_residual(x, axis_beta_y_.at(p), alpha, phi, omega_hat, bernoulli, enthalpy, r);
    return {r[0], r[1], r[2]};
  }
  const double ratio = w0 > 0 ? omega_hat / w0 : 1.0, dratio = w0 > 0 ? 1.0 / w0 : 0.0;
  const double q = axis_p_.at(p) * ratio, dq = axis_p_.at(p) * dratio;
  const double u = axis_beta_y_.at(p) * ratio + x * omega_hat, du = axis_beta_y_.at(p) * dratio + x;
  const double l = 1.0 + u * q, dl = du * q + u * dq;
  const double phi2 = phi * phi, phi4 = phi2 * phi2, alpha2 = alpha * alpha;
  const double g2 = l * l / alpha2 - q * q / phi4, dg2 = 2.0 * l * dl / alpha2 - 2.0 * q * dq / phi4;
  const double c2 = bernoulli * bernoulli;
  return {c2 * g2 - enthalpy * enthalpy, c2 * dg2, 2.0 * bernoulli * g2};
}

}  // namespace bhnsid::flow_irrotational
