#include "local_fields.hpp"

#include <fmt/format.h>

#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::horizon {

std::array<double, 6> bowen_york(const Hole& hole, const std::array<double, 3>& x) {
  const double d[3] = {x[0] - hole.position[0], x[1] - hole.position[1], x[2] - hole.position[2]};
  const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double n[3] = {d[0] / r, d[1] / r, d[2] / r};
  const double* p = hole.momentum.data();
  const double pn = p[0] * n[0] + p[1] * n[1] + p[2] * n[2], f = 1.5 / (r * r);
  std::array<double, 6> a{};
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      a[static_cast<std::size_t>(sym_index(i, j))] =
          f * (p[i] * n[j] + p[j] * n[i] - ((i == j ? 1.0 : 0.0) - n[i] * n[j]) * pn);
  return a;
}

LocalFields::LocalFields(const Grid& grid, int chi, int ahat, const Hole& hole, double half) : hole_(hole) {
  const Level& lv = grid.finest();
  dx_ = lv.dx;
  const bool mirror = lv.z_symmetry;
  const int reach = 3;  // the Lagrange stencil's two points each side, and one of slack
  std::array<int, 3> lo{}, hi{};
  const int extent[3] = {lv.nx, lv.ny, lv.nz};
  for (int a = 0; a < 3; ++a) {
    const auto s = static_cast<std::size_t>(a);
    lo[s] = static_cast<int>(std::floor((hole.position[s] - half - lv.origin[s]) / dx_)) - reach;
    hi[s] = static_cast<int>(std::ceil((hole.position[s] + half - lv.origin[s]) / dx_)) + reach;
    const int low_limit = (a == 2 && mirror) ? -(extent[a] - 1) : 0;
    if (lo[s] < low_limit || hi[s] > extent[a] - 1)
      throw core::RunFailure(fmt::format(
          "horizon: the search box about the puncture (half-width {:.4g} hatted about xhat = ({:.4g}, {:.4g}, {:.4g})) "
          "leaves the grid along {}: move the hole or enlarge the grid",
          half, hole.position[0], hole.position[1], hole.position[2], "xyz"[a]));
    n_[s] = hi[s] - lo[s] + 1;
    origin_[s] = lv.origin[s] + dx_ * lo[s];
  }
  const std::size_t count = static_cast<std::size_t>(n_[0]) * n_[1] * n_[2];
  chi_.assign(count, 0.0);
  has_zhat_ = ahat >= 0;
  if (has_zhat_)
    for (auto& z : zhat_) z.assign(count, 0.0);
  const FieldInfo* ainfo = has_zhat_ ? &grid.field_info(ahat) : nullptr;
  for (int k = 0; k < n_[2]; ++k)
    for (int j = 0; j < n_[1]; ++j)
      for (int i = 0; i < n_[0]; ++i) {
        const int gi = lo[0] + i, gj = lo[1] + j, gk = lo[2] + k;
        const int sk = gk < 0 ? -gk : gk;  // the mirror image below z = 0
        const std::ptrdiff_t p = lv.at(gi, gj, sk);
        const std::size_t q = index(i, j, k);
        chi_[q] = grid.data(chi, 0, 0)[p];
        if (!has_zhat_) continue;
        const std::array<double, 3> x{origin_[0] + dx_ * i, origin_[1] + dx_ * j, origin_[2] + dx_ * k};
        const std::array<double, 6> by = bowen_york(hole, {x[0], x[1], gk < 0 ? -x[2] : x[2]});
        for (int c = 0; c < 6; ++c) {
          const double sign = gk < 0 ? ainfo->parity[static_cast<std::size_t>(c)].z : 1.0;
          // Ahat - Ahat_BY at the stored point, carried to its image with the component's parity.
          zhat_[static_cast<std::size_t>(c)][q] = sign * (grid.data(ahat, c, 0)[p] - by[static_cast<std::size_t>(c)]);
        }
      }
}

bool LocalFields::covers(const std::array<double, 3>& x) const {
  for (int a = 0; a < 3; ++a) {
    const auto s = static_cast<std::size_t>(a);
    const double t = (x[s] - origin_[s]) / dx_;
    if (!(t >= 1.0 && t <= n_[s] - 3.0)) return false;
  }
  return true;
}

void LocalFields::sample(const std::vector<double>& f, const std::array<double, 3>& x, double& value,
                         std::array<double, 3>& grad) const {
  // Cell base b (stencil b-1 .. b+2) and the Lagrange weights and their derivatives per axis.
  int base[3];
  double w[3][4], dw[3][4];
  for (int a = 0; a < 3; ++a) {
    const auto s = static_cast<std::size_t>(a);
    const double t = (x[s] - origin_[s]) / dx_;
    base[a] = static_cast<int>(std::floor(t));
    const double u = t - base[a];
    const double nodes[4] = {-1, 0, 1, 2};
    for (int m = 0; m < 4; ++m) {
      double num = 1, den = 1, deriv = 0;
      for (int q = 0; q < 4; ++q) {
        if (q == m) continue;
        den *= nodes[m] - nodes[q];
        num *= u - nodes[q];
        double term = 1;
        for (int r = 0; r < 4; ++r)
          if (r != m && r != q) term *= u - nodes[r];
        deriv += term;
      }
      w[a][m] = num / den;
      dw[a][m] = deriv / den / dx_;
    }
  }
  value = 0;
  grad = {0, 0, 0};
  for (int c = 0; c < 4; ++c)
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a) {
        const double v = f[index(base[0] - 1 + a, base[1] - 1 + b, base[2] - 1 + c)];
        value += w[0][a] * w[1][b] * w[2][c] * v;
        grad[0] += dw[0][a] * w[1][b] * w[2][c] * v;
        grad[1] += w[0][a] * dw[1][b] * w[2][c] * v;
        grad[2] += w[0][a] * w[1][b] * dw[2][c] * v;
      }
}

FieldPoint LocalFields::at(const std::array<double, 3>& x) const {
  FieldPoint out;
  double chi = 0;
  std::array<double, 3> dchi{};
  sample(chi_, x, chi, dchi);
  const double d[3] = {x[0] - hole_.position[0], x[1] - hole_.position[1], x[2] - hole_.position[2]};
  const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double pole = 0.5 * hole_.mass / r;
  out.phi = pole + chi;
  for (int a = 0; a < 3; ++a)
    out.dlnphi[static_cast<std::size_t>(a)] = (dchi[static_cast<std::size_t>(a)] - pole * d[a] / (r * r)) / out.phi;
  out.ahat = bowen_york(hole_, x);
  if (has_zhat_)
    for (std::size_t c = 0; c < 6; ++c) {
      double z = 0;
      std::array<double, 3> unused{};
      sample(zhat_[c], x, z, unused);
      out.ahat[c] += z;
    }
  return out;
}

}  // namespace bhnsid::horizon
