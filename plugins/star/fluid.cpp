#include "fluid.hpp"

#include <cmath>
#include <memory>

namespace bhnsid::star {

void StarFluid::attach(Grid& grid, Flow& flow) {
  grid_ = &grid;
  flow_ = &flow;
  const std::vector<core::TensorKind> scalar{core::TensorKind::scalar};
  const std::vector<core::TensorKind> vector{core::TensorKind::vector_x, core::TensorKind::vector_y,
                                             core::TensorKind::vector_z};
  rho0_ = grid.add_field(fields::rho0, scalar);
  grid.add_field(fields::press, scalar);
  grid.add_field(fields::enthalpy, scalar);
  grid.add_field(fields::matter_energy, scalar);
  grid.add_field(fields::matter_trace, scalar);
  grid.add_field(fields::matter_momentum, vector, core::TimeParity::odd);
  chi_ = grid.field_id(fields::chi);
  puncture_phi_ = grid.field_id(fields::puncture_phi);
}

std::vector<std::string> StarFluid::source_inputs() const {
  std::vector<std::string> in{fields::rho0, fields::press, fields::enthalpy};
  if (flow_)
    for (const std::string& f : flow_->source_inputs()) in.push_back(f);
  return in;
}

void StarFluid::update_sources(Grid& grid, int level) const { flow_->update_sources(grid, level, flow_constants()); }

double StarFluid::rest_mass() const {
  if (!grid_) return 0.0;
  Grid& grid = *grid_;
  const Level& lv = grid.finest();
  // Every stored point is written (integrate reads no ghost), so no zero fill first.
  const auto density = std::make_unique_for_overwrite<double[]>(lv.size);
  double* d = density.get();
  flow_->velocity(grid, flow_constants(), d, nullptr);
  const double* rho0 = grid.data(rho0_, 0, 0);
  const double* chi = grid.data(chi_, 0, 0);
  const double* pphi = grid.data(puncture_phi_, 0, 0);
  // M0 = sigma^3 Int rho0 W phi^6 d^3xhat; W is NaN only at matter without a timelike velocity.
  for_stored_points(lv, [&](std::ptrdiff_t p) {
    const double phi = pphi[p] + chi[p], phi2 = phi * phi;
    d[p] = rho0[p] > 0 ? rho0[p] * d[p] * phi2 * phi2 * phi2 : 0.0;
  });
  const double s = constants.sigma;
  return s * s * s * grid.integrate(d, Parity{}, 0);
}

}  // namespace bhnsid::star
