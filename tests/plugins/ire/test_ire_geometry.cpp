// The evaluator on fields with known answers (no solver involved): its Ricci scalar, momentum
// constraint, maximal-slicing and minimal-distortion residuals against closed forms, converging at
// second order, on the real grid with equatorial symmetry.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "evaluator.hpp"
#include "grid_fill.hpp"
#include "hierarchy.hpp"
#include "uniform_grid.hpp"

using namespace bhnsid;
using namespace bhnsid::ire;
using Catch::Detail::Approx;
using bhnsid::test::fill;

namespace {

std::unique_ptr<grid::UniformGrid> make_grid(int n, double half_width) {
  grid::HierarchySpec spec;
  spec.n = n;
  spec.dx = 2 * half_width / n;
  spec.symmetry = Symmetry::equatorial;
  auto g = std::make_unique<grid::UniformGrid>(grid::build_hierarchy(spec), Symmetry::equatorial);
  const std::vector<core::TensorKind> scalar{core::TensorKind::scalar};
  const std::vector<core::TensorKind> vector{core::TensorKind::vector_x, core::TensorKind::vector_y,
                                             core::TensorKind::vector_z};
  Grid& grid = *g;
  grid.add_field(fields::chi, scalar);
  grid.add_field(fields::alpha, scalar);
  grid.add_field(fields::shift, vector, core::TimeParity::odd);
  return g;
}

/// Column `name` of the axis table as (x, value) pairs, evaluated points only.
std::vector<std::array<double, 2>> column(const Result& r, const std::string& name) {
  std::istringstream in(r.axis_table);
  std::string line, cell;
  std::getline(in, line);
  std::istringstream head(line);
  int index = -1, c = 0;
  while (std::getline(head, cell, '\t')) {
    if (cell == name) index = c;
    ++c;
  }
  REQUIRE(index > 0);
  std::vector<std::array<double, 2>> out;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::vector<std::string> cells;
    while (std::getline(row, cell, '\t')) cells.push_back(cell);
    if (cells.size() <= static_cast<std::size_t>(index) || cells[static_cast<std::size_t>(index)] == "nan") continue;
    out.push_back({std::stod(cells[0]), std::stod(cells[static_cast<std::size_t>(index)])});
  }
  return out;
}

/// Largest |residual - exact(x)| over the axis points with |x| <= reach.
template <class Exact>
double axis_error(const Result& r, const std::string& name, double reach, Exact&& exact) {
  double worst = 0;
  for (const auto& [x, v] : column(r, name))
    if (std::fabs(x) <= reach) worst = std::max(worst, std::fabs(v - exact(x)));
  return worst;
}

}  // namespace

TEST_CASE("plugins.ire.ricci_scalar_of_a_conformally_flat_metric", "[plugins][ire]") {
  // phi = 1 + a G, G = exp(-r^2/w^2), no K, no matter, no shift, alpha = 1: the
  // Hamiltonian residual is the Ricci scalar, R = -8 phi^-5 lap phi, from the evaluator's generic
  // Christoffel symbols and Ricci tensor (which assume nothing about the metric's form). Its
  // error on the x axis falls by 4 per halving; the maximal-slicing residual -D^2 alpha + alpha R
  // with alpha = 1 is R too.
  const double a = 0.2, w = 0.5;
  auto phi = [&](double x, double y, double z) { return 1 + a * std::exp(-(x * x + y * y + z * z) / (w * w)); };
  auto ricci = [&](double x) {
    const double g = std::exp(-x * x / (w * w));
    const double lap = a * g * (4 * x * x / (w * w * w * w) - 6 / (w * w));
    return -8 * lap / std::pow(1 + a * g, 5);
  };
  double errors[2], lapse_errors[2];
  for (int q = 0; q < 2; ++q) {
    auto g = make_grid(32 << q, 2.0);
    fill(*g, fields::chi, 0, phi);
    fill(*g, fields::alpha, 0, [](double, double, double) { return 1.0; });
    Inputs in;
    const Result r = evaluate(*g, in);
    errors[q] = axis_error(r, "hamiltonian", 1.5, ricci);
    lapse_errors[q] = axis_error(r, "lapse", 1.5, ricci);
    CHECK(r.away.at("momentum").max == 0.0);
    CHECK(r.away.at("shift").max == 0.0);
  }
  INFO("R errors " << errors[0] << ", " << errors[1] << "; lapse " << lapse_errors[0] << ", " << lapse_errors[1]);
  CHECK(errors[0] / errors[1] == Approx(4.0).margin(0.5));
  CHECK(lapse_errors[0] / lapse_errors[1] == Approx(4.0).margin(0.5));
  CHECK(errors[1] < 0.02 * 8 * 6 * a / (w * w));  // small next to the curvature itself
}

TEST_CASE("plugins.ire.schwarzschild_and_bowen_york_satisfy_the_constraints", "[plugins][ire]") {
  // The puncture data chi = 1, alpha = (1 - M/(2 r))/(1 + M/(2 r)) (phi = 1 + M/(2 r): Schwarzschild, maximally
  // sliced) satisfy every equation exactly; with a Bowen-York momentum the momentum constraint
  // still holds exactly (Ahat_BY is divergence-free and traceless), while the Hamiltonian one does
  // not (chi = 1 is not its solution). Away from the puncture (its region the same length at both
  // resolutions) the residuals fall by 4 per halving in the L2 norm; Hamiltonian and lapse vanish
  // to the truncation error; the momentum residual of Bowen-York too.
  const double m = 1.0;
  const std::array<double, 3> x_bh{0.1, 0.0, 0.0};
  Norms h[2], lapse[2], mom[2];
  for (int q = 0; q < 2; ++q) {
    auto g = make_grid(32 << q, 4.0);
    fill(*g, fields::chi, 0, [](double, double, double) { return 1.0; });
    fill(*g, fields::alpha, 0, [&](double x, double y, double z) {
      const double m_2r = m / (2 * std::hypot(x - x_bh[0], y - x_bh[1], z - x_bh[2]));
      return (1 - m_2r) / (1 + m_2r);
    });
    Inputs in;
    in.puncture = true;
    in.bare_mass = m;
    in.position = x_bh;
    in.exclude_cells = 3 << q;  // 0.75 beyond the cube at both resolutions
    const Result r = evaluate(*g, in);
    h[q] = r.away.at("hamiltonian");
    lapse[q] = r.away.at("lapse");
    in.momentum = {0.0, 0.3, 0.0};
    mom[q] = evaluate(*g, in).away.at("momentum");
  }
  INFO("H " << h[0].l2 << " -> " << h[1].l2 << ", lapse " << lapse[0].l2 << " -> " << lapse[1].l2 << ", momentum "
            << mom[0].l2 << " -> " << mom[1].l2);
  CHECK(h[0].l2 / h[1].l2 == Approx(4.0).margin(0.6));
  CHECK(lapse[0].l2 / lapse[1].l2 == Approx(4.0).margin(0.6));
  CHECK(mom[0].l2 / mom[1].l2 == Approx(4.0).margin(0.6));
  CHECK(mom[1].points > 1000);
}

TEST_CASE("plugins.ire.minimal_distortion_of_a_flat_space_shift", "[plugins][ire]") {
  // Flat space (chi = alpha = 1, no K): Sigma_ij = (L beta)_ij and D^j Sigma_ij = lap beta_i +
  // (1/3) d_i div beta. For beta = (0, G, 0), G = exp(-r^2/w^2), on the x axis (y = z = 0) the
  // y component is lap G = G (4 x^2/w^4 - 6/w^2) (d_y div beta = G_yy = -2G/w^2 there, times 1/3).
  const double w = 0.6;
  auto gauss = [&](double x, double y, double z) { return std::exp(-(x * x + y * y + z * z) / (w * w)); };
  auto exact = [&](double x) {
    const double g = std::exp(-x * x / (w * w));
    return g * (4 * x * x / (w * w * w * w) - 6 / (w * w)) + g * (-2 / (w * w)) / 3;
  };
  double errors[2];
  for (int q = 0; q < 2; ++q) {
    auto g = make_grid(32 << q, 2.0);
    fill(*g, fields::chi, 0, [](double, double, double) { return 1.0; });
    fill(*g, fields::alpha, 0, [](double, double, double) { return 1.0; });
    fill(*g, fields::shift, 1, gauss);
    const Result r = evaluate(*g, Inputs{});
    errors[q] = axis_error(r, "shift_y", 1.5, exact);
  }
  INFO("errors " << errors[0] << ", " << errors[1]);
  CHECK(errors[0] / errors[1] == Approx(4.0).margin(0.5));
}

TEST_CASE("plugins.ire.stride_evaluates_at_the_coarse_points", "[plugins][ire]") {
  // With stride 2 the residuals are those of stride 1 at the points of the grid twice as coarse.
  auto g = make_grid(32, 2.0);
  fill(*g, fields::chi, 0, [](double x, double y, double z) { return 1 + 0.1 * std::exp(-(x * x + 2 * y * y + z * z)); });
  fill(*g, fields::alpha, 0, [](double x, double y, double z) {
    return (1 + 0.05 * x) / (1 + 0.1 * std::exp(-(x * x + 2 * y * y + z * z)));
  });
  Inputs in;
  const Result all = evaluate(*g, in);
  in.stride = 2;
  const Result half = evaluate(*g, in);
  const auto a = column(all, "hamiltonian"), b = column(half, "hamiltonian");
  REQUIRE(b.size() > 5);
  CHECK(b.size() * 2 <= a.size() + 2);
  std::size_t matched = 0;
  for (const auto& [x, v] : b)
    for (const auto& [xa, va] : a)
      if (std::fabs(x - xa) < 1e-12) {
        CHECK(v == Approx(va).epsilon(1e-12));
        ++matched;
      }
  CHECK(matched == b.size());
}
