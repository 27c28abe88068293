#pragma once
// TEST ONLY: a "star" Fluid for the equation plugins' manufactured-solution tests. The fluid moves
// with a stored coordinate velocity V (field test_fluid_velocity, any shape, not a corotation), so
// that v^i = (beta^i + V^i)/alpha, W^2 = 1/(1 - phi^4 |v|^2), and the projections
// rho_E = rho0 h W^2 - P, S = rho0 h (W^2 - 1) + 3P, j^i = rho0 h W^2 v^i. It is written here, apart
// from hydro_corotating's kinematics, so that the equations' tests do not rest on that plugin.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::test {

inline constexpr const char* test_fluid_velocity = "test_fluid_velocity";

/// TEST ONLY: the "lapse" of a stand-in that registers eta, chi, puncture_phi and alpha itself and
/// fills eta with a manufactured function: alpha = eta / (puncture_phi + chi), regular part eta.
class EtaOverPhiLapse final : public Lapse {
 public:
  void update(Grid& grid, int level) const override {
    const int id = grid.field_id(fields::alpha);
    double* alpha = grid.data(id, 0, level);
    const double* eta = grid.data(grid.field_id(fields::eta), 0, level);
    const double* chi = grid.data(grid.field_id(fields::chi), 0, level);
    const double* pphi = grid.data(grid.field_id(fields::puncture_phi), 0, level);
    for_stored_points(grid.level(level), [&](std::ptrdiff_t p) { alpha[p] = eta[p] / (pphi[p] + chi[p]); });
    grid.fill_ghosts(id, level);
  }
  std::string regular_part() const override { return fields::eta; }
};

class FieldVelocityFluid final : public Fluid {
 public:
  double sigma() const override { return sigma_value; }
  std::array<double, 3> centre() const override { return {0.0, 0.0, 0.0}; }
  double rest_mass() const override { return std::nan(""); }
  std::vector<std::string> source_inputs() const override {
    return {fields::rho0, fields::press, fields::enthalpy, test_fluid_velocity};
  }

  /// Registers the fluid fields and the projections; returns the ids rho0, press, enthalpy, V.
  std::array<int, 4> attach(Grid& grid) const {
    const std::vector<core::TensorKind> scalar{core::TensorKind::scalar};
    const std::vector<core::TensorKind> vector{core::TensorKind::vector_x, core::TensorKind::vector_y,
                                               core::TensorKind::vector_z};
    grid.add_field(fields::matter_energy, scalar);
    grid.add_field(fields::matter_trace, scalar);
    grid.add_field(fields::matter_momentum, vector, core::TimeParity::odd);
    return {grid.add_field(fields::rho0, scalar), grid.add_field(fields::press, scalar),
            grid.add_field(fields::enthalpy, scalar), grid.add_field(test_fluid_velocity, vector, core::TimeParity::odd)};
  }

  void update_sources(Grid& grid, int level) const override {
    const Level& lv = grid.level(level);
    auto at = [&](const char* name, int c = 0) { return grid.data(grid.field_id(name), c, level); };
    const double *rho0 = at(fields::rho0), *press = at(fields::press), *h = at(fields::enthalpy);
    const double *chi = at(fields::chi), *eta = at(fields::eta), *pphi = at(fields::puncture_phi);
    const bool shift = grid.has_field(fields::shift);
    const double* vel[3] = {at(test_fluid_velocity, 0), at(test_fluid_velocity, 1), at(test_fluid_velocity, 2)};
    const double* beta[3] = {shift ? at(fields::shift, 0) : nullptr, shift ? at(fields::shift, 1) : nullptr,
                             shift ? at(fields::shift, 2) : nullptr};
    double *energy = at(fields::matter_energy), *trace = at(fields::matter_trace);
    double* j[3] = {at(fields::matter_momentum, 0), at(fields::matter_momentum, 1), at(fields::matter_momentum, 2)};
#pragma omp parallel for schedule(static)
    for (int k = 0; k < lv.nz; ++k)
      for (int jj = 0; jj < lv.ny; ++jj)
        for (int i = 0; i < lv.nx; ++i) {
          const std::ptrdiff_t p = lv.at(i, jj, k);
          double u[3], u2 = 0;
          for (int c = 0; c < 3; ++c) {
            u[c] = vel[c][p] + (shift ? beta[c][p] : 0.0);
            u2 += u[c] * u[c];
          }
          const double phi = pphi[p] + chi[p], alpha = eta[p] / phi, phi2 = phi * phi;
          const double v2 = phi2 * phi2 * u2 / (alpha * alpha), w2 = 1.0 / (1.0 - v2);
          const bool matter = rho0[p] > 0;
          const double rh = rho0[p] * h[p];
          energy[p] = matter ? rh * w2 - press[p] : 0.0;
          trace[p] = matter ? rh * (w2 - 1.0) + 3.0 * press[p] : 0.0;
          for (int c = 0; c < 3; ++c) j[c][p] = matter ? rh * w2 * u[c] / alpha : 0.0;
        }
  }

  double sigma_value = 1;
};

}  // namespace bhnsid::test
