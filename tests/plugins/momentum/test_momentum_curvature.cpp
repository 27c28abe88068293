// The momentum plugin's second job: Ahat^ij = Ahat_BY^ij + Zhat^ij and aa_hat on every level of the
// real (serial) grid.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "hierarchy.hpp"
#include "momentum.hpp"
#include "test_fluid.hpp"
#include "uniform_grid.hpp"

using namespace bhnsid;
using Catch::Detail::Approx;

namespace {

class FakePuncture final : public Puncture {
 public:
  double bare_mass() const override { return 0.5; }
  std::array<double, 3> position() const override { return x; }
  std::array<double, 3> momentum() const override { return p; }
  std::array<double, 3> x{}, p{};
};

std::unique_ptr<grid::UniformGrid> make_grid(int n, double dx, Symmetry symmetry) {
  grid::HierarchySpec spec;
  spec.n = n;
  spec.dx = dx;
  spec.symmetry = symmetry;
  return std::make_unique<grid::UniformGrid>(grid::build_hierarchy(spec), symmetry);
}

/// Registers chi, eta, puncture_phi as the hamiltonian and lapse plugins would and fills chi and eta
/// on the finest level only (the fill must not need the coarse ones).
template <class Chi, class Eta>
void add_chi_eta(Grid& g, Chi&& chi_of, Eta&& eta_of) {
  const int chi = g.add_field(fields::chi, {core::TensorKind::scalar});
  const int eta = g.add_field(fields::eta, {core::TensorKind::scalar});
  g.add_field(fields::puncture_phi, {core::TensorKind::scalar});
  const Level& lv = g.finest();
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        g.data(chi, 0, 0)[lv.at(i, j, k)] = chi_of(lv.x(i), lv.y(j), lv.z(k));
        g.data(eta, 0, 0)[lv.at(i, j, k)] = eta_of(lv.x(i), lv.y(j), lv.z(k));
      }
  g.fill_ghosts(chi, 0);
  g.fill_ghosts(eta, 0);
}

std::array<double, 6> ahat_at(Grid& g, int l, int i, int j, int k) {
  const int id = g.field_id(fields::ahat);
  std::array<double, 6> t{};
  for (int m = 0; m < 6; ++m) t[static_cast<std::size_t>(m)] = g.data(id, m, l)[g.level(l).at(i, j, k)];
  return t;
}

/// The lapse of the stand-in fields: its regular part, eta, is the ansatz weight.
const test::EtaOverPhiLapse eta_lapse;

}  // namespace

TEST_CASE("plugins.momentum.bowen_york_fill", "[plugins][momentum]") {
  // With a puncture and W = 0, ahat must be the Bowen-York tensor on every level and aa_hat =
  // 9 P^2 (1 + 2 cos^2 theta) / (2 r^4) with cos theta = n.P/|P| (physics-notes §2.6), traceless,
  // the ghost plane below z = 0 mirroring it with Ahat^xz, Ahat^yz odd.
  auto g = make_grid(32, 0.06, Symmetry::equatorial);
  add_chi_eta(*g, [](double x, double, double) { return 1.1 + 0.1 * x; }, [](double, double y, double) { return 0.8 + 0.05 * y; });
  FakePuncture hole;
  hole.x = {-0.1871, 0.0, 0.0};
  hole.p = {0.12, -0.35, 0.0};
  momentum::MomentumEquation eq(*g, &eta_lapse, momentum::Weight::lapse, nullptr, &hole, 1.0);
  eq.fill_curvature();
  const double p2 = 0.12 * 0.12 + 0.35 * 0.35;
  const int aa_id = g->field_id(fields::aa);
  int checked = 0;
  for (int l = 0; l < g->num_levels(); ++l) {
    const Level& lv = g->level(l);
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j)
        for (int i = 0; i < lv.nx; ++i) {
          const std::array<double, 3> x{lv.x(i), lv.y(j), lv.z(k)};
          const auto a = ahat_at(*g, l, i, j, k);
          const auto by = momentum::bowen_york(hole.p, hole.x, x);
          const double d[3] = {x[0] - hole.x[0], x[1] - hole.x[1], x[2] - hole.x[2]};
          const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
          const double cos_theta = (d[0] * hole.p[0] + d[1] * hole.p[1] + d[2] * hole.p[2]) / (r * std::sqrt(p2));
          const double aa = 9 * p2 * (1 + 2 * cos_theta * cos_theta) / (2 * std::pow(r, 4));
          INFO("level " << l << " point (" << x[0] << ", " << x[1] << ", " << x[2] << ")");
          for (std::size_t m = 0; m < 6; ++m) REQUIRE(a[m] == Approx(by[m]).epsilon(1e-13).margin(1e-13 * std::sqrt(aa)));
          REQUIRE(a[0] + a[3] + a[5] == Approx(0).margin(1e-12 * std::sqrt(aa)));
          REQUIRE(g->data(aa_id, 0, l)[lv.at(i, j, k)] == Approx(aa).epsilon(1e-12));
          if (k == 1) {
            const auto ghost = ahat_at(*g, l, i, j, -1);
            for (std::size_t m = 0; m < 6; ++m) REQUIRE(ghost[m] == ((m == 2 || m == 4) ? -a[m] : a[m]));
          }
          ++checked;
        }
  }
  CHECK(checked > 33 * 33 * 17);
}

TEST_CASE("plugins.momentum.zhat_fill_is_exact_for_quadratic_w", "[plugins][momentum]") {
  // Without a puncture ahat must be Zhat = chi^7/(2 eta) (LW)^ij at every stored point of every level,
  // faces and the z = 0 plane included, from the finest level's W, chi, eta: the centred and one-sided
  // second-order differences are exact for a quadratic W (with W^z odd in z), so the fill must match
  // the analytic LW to rounding even where the coarse levels' own arrays hold zeros.
  for (Symmetry symmetry : {Symmetry::equatorial, Symmetry::none}) {
    auto g = make_grid(16, 0.1, symmetry);
    auto chi_of = [](double x, double y, double z) { return 1.2 + 0.1 * x * x - 0.05 * y + 0.02 * z * z; };
    auto eta_of = [](double x, double y, double) { return 0.9 - 0.1 * x * y + 0.03 * y; };
    add_chi_eta(*g, chi_of, eta_of);
    momentum::MomentumEquation eq(*g, &eta_lapse, momentum::Weight::lapse, nullptr, nullptr, 1.0);
    const int w = g->field_id(fields::wvec);
    const Level& fine = g->finest();
    for (int k = -1; k <= fine.nz; ++k)
      for (int j = -1; j <= fine.ny; ++j)
        for (int i = -1; i <= fine.nx; ++i) {
          const double x = fine.x(i), y = fine.y(j), z = fine.z(k);
          const std::ptrdiff_t p = fine.at(i, j, k);
          g->data(w, 0, 0)[p] = 0.3 + 0.5 * x - 0.2 * y + 0.7 * x * y - 0.4 * z * z + 0.25 * x * x;
          g->data(w, 1, 0)[p] = -0.1 + 0.3 * x + 0.6 * y - 0.5 * x * x + 0.3 * z * z;
          g->data(w, 2, 0)[p] = z * (0.4 - 0.6 * x + 0.8 * y);
        }
    eq.fill_curvature();
    const int aa_id = g->field_id(fields::aa);
    for (int l = 0; l < g->num_levels(); ++l) {
      const Level& lv = g->level(l);
      for (int k = 0; k < lv.nz; ++k)
        for (int j = 0; j < lv.ny; ++j)
          for (int i = 0; i < lv.nx; ++i) {
            const double x = lv.x(i), y = lv.y(j), z = lv.z(k);
            // d_j W^a
            const double dw[3][3] = {{0.5 + 0.7 * y + 0.5 * x, -0.2 + 0.7 * x, -0.8 * z},
                                     {0.3 - x, 0.6, 0.6 * z},
                                     {-0.6 * z, 0.8 * z, 0.4 - 0.6 * x + 0.8 * y}};
            const double div = dw[0][0] + dw[1][1] + dw[2][2];
            const double factor = std::pow(chi_of(x, y, z), 7) / (2 * eta_of(x, y, z));
            const auto a = ahat_at(*g, l, i, j, k);
            INFO((symmetry == Symmetry::none ? "full cube" : "equatorial") << ", level " << l << " point (" << i << ", "
                                                                            << j << ", " << k << ")");
            for (int r = 0; r < 3; ++r)
              for (int c = r; c < 3; ++c) {
                const double lw = dw[c][r] + dw[r][c] - (r == c ? 2.0 / 3.0 * div : 0.0);
                REQUIRE(a[static_cast<std::size_t>(sym_index(r, c))] == Approx(factor * lw).margin(1e-10));
              }
            REQUIRE(g->data(aa_id, 0, l)[lv.at(i, j, k)] == Approx(momentum::squared_norm(a)).epsilon(1e-14));
          }
    }
  }
}

TEST_CASE("plugins.momentum.refuses_a_puncture_on_a_grid_point", "[plugins][momentum]") {
  // The Bowen-York tensor is infinite at the puncture: a hole on a point of any level must fail with
  // a message, not fill NaN into aa_hat.
  auto g = make_grid(16, 0.1, Symmetry::equatorial);
  add_chi_eta(*g, [](double, double, double) { return 1.0; }, [](double, double, double) { return 1.0; });
  FakePuncture hole;
  hole.x = {0.4, 0.0, 0.0};  // a point of level 2 (spacing 0.4), not of level 0's neighbours only
  hole.p = {0.0, 0.3, 0.0};
  momentum::MomentumEquation eq(*g, &eta_lapse, momentum::Weight::lapse, nullptr, &hole, 1.0);
  CHECK_THROWS_AS(eq.fill_curvature(), core::RunFailure);
  hole.x = {0.4 + 0.013, 0.0, 0.0};
  CHECK_NOTHROW(eq.fill_curvature());
}

TEST_CASE("plugins.momentum.the_ansatz_weight_is_free_and_must_be_positive", "[plugins][momentum]") {
  // Zhat = chi^7/(2 q) (LW): q = 1 (momentum.weight: unit) gives chi^7/2 (LW) whatever eta is, and a
  // weight that is not positive somewhere (the regular part of a lapse gone wrong) stops the fill with
  // a RunFailure naming the point, never a Zhat of the wrong sign.
  auto g = make_grid(16, 0.1, Symmetry::equatorial);
  add_chi_eta(*g, [](double, double, double) { return 1.1; }, [](double x, double, double) { return x > 0.3 ? -0.2 : 0.7; });
  momentum::MomentumEquation unit(*g, nullptr, momentum::Weight::unit, nullptr, nullptr, 1.0);
  const int w = g->field_id(fields::wvec);
  const Level& fine = g->finest();
  for (int k = -1; k <= fine.nz; ++k)
    for (int j = -1; j <= fine.ny; ++j)
      for (int i = -1; i <= fine.nx; ++i) g->data(w, 0, 0)[fine.at(i, j, k)] = 0.3 * fine.x(i);  // (LW)^xx = 0.4
  unit.fill_curvature();
  const int ahat = g->field_id(fields::ahat);
  CHECK(g->data(ahat, 0, 0)[fine.at(8, 8, 2)] == Approx(0.5 * std::pow(1.1, 7) * 0.4).epsilon(1e-12));
  momentum::MomentumEquation by_lapse(*g, &eta_lapse, momentum::Weight::lapse, nullptr, nullptr, 1.0);
  CHECK_THROWS_WITH(by_lapse.fill_curvature(), Catch::Matchers::Contains("ansatz weight q = -0.2") &&
                                                   Catch::Matchers::Contains("not positive"));
}
