// The star's rest mass M0 = sigma^3 Int rho0 W phi^6 d^3xhat on a grid, W from its flow.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <numbers>

#include "fluid.hpp"
#include "grid_fill.hpp"
#include "real_grid.hpp"

using namespace bhnsid;
using namespace bhnsid::star;
using Catch::Detail::Approx;

namespace {

/// A flow with a uniform Lorentz factor, which is all the rest mass reads of it.
class UniformLorentz final : public Flow {
 public:
  explicit UniformLorentz(double w) : w_(w) {}
  std::string kind() const override { return "uniform"; }
  void update_sources(Grid&, int, const FlowConstants&) const override {}
  void velocity(Grid& grid, const FlowConstants&, double* lorentz, double* const*) const override {
    for_stored_points(grid.finest(), [&](std::ptrdiff_t p) { lorentz[p] = w_; });
  }
  std::string acausal_matter(Grid&, const FlowConstants&) const override { return {}; }
  void enthalpy(Grid&, const FlowConstants&, const double*, const double*, double*) const override {}
  void first_integral(Grid&, const FlowConstants&, double*) const override {}
  void freeze_axis(Grid&, const std::vector<double>&, const FlowConstants&) override {}
  AxisResidual axis_residual(std::size_t, double, double, double, double, double) const override { return {}; }

 private:
  double w_;
};

}  // namespace

TEST_CASE("plugins.star.rest_mass_of_a_gaussian", "[plugins][star]") {
  // phi = 1 and W = 1.25: M0 = 1.25 sigma^3 Int rho0 = 1.25 sigma^3 a pi^(3/2) s^3 (trapezoid rule,
  // smooth decayed integrand: far below 1e-8 at n = 32).
  auto g = test::equatorial_grid(32, 0.125, {fields::chi, fields::puncture_phi});
  StarFluid fluid;
  UniformLorentz flow(1.25);
  fluid.attach(*g, flow);
  fluid.constants.sigma = 1.3;
  const double a = 0.02, s = 0.4;
  test::fill(*g, fields::chi, 0, [](double, double, double) { return 1.0; });
  test::fill(*g, fields::rho0, 0, [&](double x, double y, double z) { return a * std::exp(-(x * x + y * y + z * z) / (s * s)); });
  CHECK(fluid.rest_mass() == Approx(1.25 * std::pow(1.3, 3) * a * std::pow(std::numbers::pi, 1.5) * s * s * s).epsilon(1e-8));
  // phi = 1.1 everywhere: phi^6 more.
  test::fill(*g, fields::chi, 0, [](double, double, double) { return 1.1; });
  CHECK(fluid.rest_mass() == Approx(1.25 * std::pow(1.1, 6) * std::pow(1.3, 3) * a * std::pow(std::numbers::pi, 1.5) * s * s * s)
                                 .epsilon(1e-8));
}
