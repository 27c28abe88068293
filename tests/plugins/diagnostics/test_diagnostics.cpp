// The diagnostics plugin's integrals on fields with known answers, on the real grid with equatorial
// symmetry (so the mirrored half and the z = 0 plane are counted as the plugin claims).
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "grid_fill.hpp"
#include "hierarchy.hpp"
#include "real_grid.hpp"
#include "integrals.hpp"
#include "surface.hpp"
#include "uniform_grid.hpp"

using namespace bhnsid;
using namespace bhnsid::diagnostics;
using Catch::Detail::Approx;
using bhnsid::test::fill;

namespace {


/// Level 0 of n intervals on [-2, 2]^3 (z >= 0 stored), with the fields masses() reads registered.
std::unique_ptr<grid::UniformGrid> make_grid(int n) {
  return test::equatorial_grid(n, 4.0 / n, {fields::chi, fields::puncture_phi, fields::aa, fields::matter_energy});
}

/// The Bowen-York tensor (physics-notes §2.6), written here as the test's reference.
std::array<double, 6> bowen_york(const std::array<double, 3>& p, const std::array<double, 3>& xbh, const std::array<double, 3>& x) {
  double n[3], r2 = 0;
  for (int a = 0; a < 3; ++a) n[a] = x[static_cast<std::size_t>(a)] - xbh[static_cast<std::size_t>(a)], r2 += n[a] * n[a];
  const double r = std::sqrt(r2);
  double pn = 0;
  for (int a = 0; a < 3; ++a) n[a] /= r, pn += p[static_cast<std::size_t>(a)] * n[a];
  std::array<double, 6> out{};
  int q = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b)
      out[static_cast<std::size_t>(q++)] = 1.5 / r2 *
          (p[static_cast<std::size_t>(a)] * n[b] + p[static_cast<std::size_t>(b)] * n[a] - ((a == b ? 1.0 : 0.0) - n[a] * n[b]) * pn);
  return out;
}

}  // namespace

TEST_CASE("plugins.diagnostics.falloff_mass_is_exact_for_a_monopole", "[plugins][diagnostics]") {
  // chi = 1 + c/|x - x0| has rhat (chi - 1) = c on every face, so the solid-angle mean gives
  // M_ADM = sigma (Mhat + 2c) to round-off, whatever the weights, centre or resolution.
  auto g = make_grid(32);
  const std::array<double, 3> x0{0.3, -0.2, 0.0};
  const double c = 0.07;
  fill(*g, fields::chi, 0, [&](double x, double y, double z) { return 1 + c / std::hypot(x - x0[0], y - x0[1], z - x0[2]); });
  Inputs in;
  in.sigma = 1.5;
  in.bh_bare_mass = 0.4;
  in.centre = x0;
  CHECK(masses(*g, in).adm_mass_falloff == Approx(1.5 * (0.4 + 2 * c)).epsilon(1e-13));
}

TEST_CASE("plugins.diagnostics.volume_mass_of_a_gaussian", "[plugins][diagnostics]") {
  // phi = 1 and rho_E = a exp(-r^2/s^2) (dust at rest, as the star would give it):
  // M_ADM = sigma^3 Int rho_E = sigma^3 a pi^(3/2) s^3; the trapezoid rule on a smooth, decayed
  // integrand is accurate far below 1e-8 at n = 32.
  auto g = make_grid(32);
  const double a = 0.02, s = 0.4, sigma = 1.3;
  fill(*g, fields::chi, 0, [](double, double, double) { return 1.0; });
  fill(*g, fields::matter_energy, 0, [&](double x, double y, double z) { return a * std::exp(-(x * x + y * y + z * z) / (s * s)); });
  Inputs in;
  in.sigma = sigma;
  const Masses m = masses(*g, in);
  const double exact = sigma * sigma * sigma * a * std::pow(std::numbers::pi, 1.5) * s * s * s;
  CHECK(m.adm_mass_volume == Approx(exact).epsilon(1e-8));
}

TEST_CASE("plugins.diagnostics.surface_momenta_of_a_bowen_york_hole", "[plugins][diagnostics]") {
  // For the Bowen-York Ahat of a hole at x_BH with momentum P, (1/8pi) oint Ahat^ij dS_j = P^i and
  // the angular momentum about the origin is x_BH P^y - y_BH P^x (physics-notes §2.6), on any
  // surface around the hole: the face integrals must approach them at second order in dx.
  const std::array<double, 3> p{0.1, 0.3, 0.0}, xbh{0.25, 0.0, 0.0};
  std::array<double, 3> previous{};
  for (int n : {32, 64}) {
    auto g = make_grid(n);
    // As the momentum plugin registers it: a time-odd symmetric tensor.
    static_cast<Grid&>(*g).add_field(fields::ahat,
                                     {core::TensorKind::tensor_xx, core::TensorKind::tensor_xy, core::TensorKind::tensor_xz,
                                      core::TensorKind::tensor_yy, core::TensorKind::tensor_yz, core::TensorKind::tensor_zz},
                                     core::TimeParity::odd);
    for (int c = 0; c < 6; ++c)
      fill(*g, fields::ahat, c, [&](double x, double y, double z) { return bowen_york(p, xbh, {x, y, z})[static_cast<std::size_t>(c)]; });
    const double sigma = 2.0;
    const SurfaceMomenta s = surface_momenta(*g, sigma);
    const std::array<double, 3> err{s.momentum_x / sigma - p[0], s.momentum_y / sigma - p[1],
                                    s.angular_momentum_z / (sigma * sigma) - xbh[0] * p[1]};
    INFO("n = " << n << ": errors " << err[0] << ", " << err[1] << ", " << err[2]);
    for (std::size_t q = 0; q < 3; ++q) {
      CHECK(std::fabs(err[q]) < 5e-3 * std::fabs(p[1]));
      if (n == 64) CHECK(std::fabs(previous[q]) / std::fabs(err[q]) == Approx(4.0).margin(0.8));
    }
    previous = err;
  }
}

namespace {

/// (1/16pi) Int_outside A(n)/r^p d^3x over the outside of the cube [-a, a]^3, = (1/16pi)
/// Int A(n) r_face(n)^(3-p)/(p-3) dOmega, by a 400 x 400 Gauss-midpoint rule on each face
/// (dOmega = a du dv / r^3): the test's independent reference.
template <class A>
double outside_reference(double a, int p, A&& angular) {
  const int m = 400;
  double sum = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0})
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) {
          double x[3];
          x[axis] = sign * a;
          x[(axis + 1) % 3] = a * (-1 + (i + 0.5) * 2.0 / m);
          x[(axis + 2) % 3] = a * (-1 + (j + 0.5) * 2.0 / m);
          const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
          const double d_omega = a * (2.0 * a / m) * (2.0 * a / m) / (r * r * r);
          sum += angular(x, r) * std::pow(r, 3 - p) / (p - 3) * d_omega;
        }
  return sum / (16 * std::numbers::pi);
}

}  // namespace

TEST_CASE("plugins.diagnostics.outside_mass_of_a_net_momentum_tail", "[plugins][diagnostics]") {
  // AA = 9 P^2 (1 + 2 cos^2 theta) / (2 r^4) (the Bowen-York AA of a momentum P along y) beyond the
  // cube is the r^-4 part; the face sum must agree with the quadrature at second order in dx, and
  // leave no remainder.
  const double a = 2.0, pm = 0.3;
  auto aa = [&](const double* x, double r) { return 4.5 * pm * pm * (1 + 2 * x[1] * x[1] / (r * r)) / std::pow(r, 4); };
  const double exact = outside_reference(a, 4, [&](const double* x, double r) { return aa(x, r) * std::pow(r, 4); });
  double previous = 0;
  for (int n : {32, 64}) {
    auto g = make_grid(n);
    fill(*g, fields::aa, 0, [&](double x, double y, double z) {
      const double p[3] = {x, y, z};
      return aa(p, std::sqrt(x * x + y * y + z * z));
    });
    const OutsideMass o = outside_aa_mass(*g, 1.0, {0, 0, 0}, {0.0, pm});
    const double err = o.total() - exact;
    INFO("n = " << n << ": outside mass error " << err << " of " << exact << ", remainder " << o.remainder);
    CHECK(std::fabs(err) < 2e-3 * exact);
    CHECK(std::fabs(o.remainder) < 1e-12 * exact);
    if (previous != 0) CHECK(previous / err == Approx(4.0).margin(0.8));
    previous = err;
  }
}

TEST_CASE("plugins.diagnostics.outside_mass_without_net_momentum_falls_faster", "[plugins][diagnostics]") {
  // Zero net momentum: AA = (1 + x^2/r^2)/r^6 (Ahat ~ r^-3) leaves (1/16pi) Int A(n) dOmega/(3 r_face^3)
  // outside the cube, a third of what an r^-4 reading of the same face values would give.
  const double a = 2.0;
  const double exact = outside_reference(a, 6, [](const double* x, double r) { return 1 + x[0] * x[0] / (r * r); });
  double previous = 0;
  for (int n : {32, 64}) {
    auto g = make_grid(n);
    fill(*g, fields::aa, 0, [](double x, double y, double z) {
      const double r2 = x * x + y * y + z * z;
      return (1 + x * x / r2) / (r2 * r2 * r2);
    });
    const OutsideMass o = outside_aa_mass(*g, 1.0, {0, 0, 0}, {0.0, 0.0});
    const double err = o.total() - exact;
    INFO("n = " << n << ": outside mass error " << err << " of " << exact);
    CHECK(o.net_momentum == 0.0);
    CHECK(std::fabs(err) < 2e-3 * exact);
    if (previous != 0) CHECK(previous / err == Approx(4.0).margin(0.8));
    previous = err;
  }
}

TEST_CASE("plugins.diagnostics.matter_needs_its_projections", "[plugins][diagnostics]") {
  // A fluid whose plugin registered no matter_energy is refused, never read through null.
  auto g = test::equatorial_grid(16, 0.25, {fields::chi});
  Inputs in;
  in.matter = true;
  CHECK_THROWS_AS(masses(*g, in), core::RunFailure);
}

TEST_CASE("plugins.diagnostics.surface_flux_mass_of_a_monopole_converges", "[plugins][diagnostics]") {
  // chi = 1 + c/|x - x0| with x0 inside: Gauss's theorem gives -(1/2pi) oint d_n chi dS = 2c exactly,
  // so M = sigma (Mhat + 2c). The one-sided derivative and the trapezoid faces are second order:
  // the error falls by 4 (3.5 .. 4.5) from n = 32 to 64 to 128 on the same cube.
  const std::array<double, 3> x0{0.3, -0.2, 0.0};
  const double c = 0.07, sigma = 1.5, mhat = 0.4;
  double error[3];
  for (int q = 0; q < 3; ++q) {
    auto g = make_grid(32 << q);
    fill(*g, fields::chi, 0, [&](double x, double y, double z) { return 1 + c / std::hypot(x - x0[0], y - x0[1], z - x0[2]); });
    error[q] = surface_flux_mass(*g, sigma, mhat) - sigma * (mhat + 2 * c);
  }
  INFO("errors " << error[0] << ", " << error[1] << ", " << error[2]);
  CHECK(error[0] / error[1] == Approx(4.0).margin(0.5));
  CHECK(error[1] / error[2] == Approx(4.0).margin(0.5));
  CHECK(std::fabs(error[2]) < 1e-3 * sigma * 2 * c);
}
