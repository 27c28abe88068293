#pragma once
// The singular-term maximal-slicing lapse (kernels.hpp) as an EllipticEquation ("equation.lapse",
// unknown eta_regular = eta~, Robin falloff eta~ -> 1) and as the "lapse" service (alpha from eta~,
// chi, puncture_phi and c). Both read c from one Strength, which the virial condition updates.
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "kernels.hpp"

namespace bhnsid::lapse_komar {

inline constexpr const char* eta_regular = "eta_regular";

/// c of eta = eta~ - c Mhat/(2 rhat), shared by the equation and the lapse service.
struct Strength {
  double c = 1;
};

class KomarEquation final : public EllipticEquation {
 public:
  /// Registers eta_regular and alpha; reads chi, puncture_phi and aa_hat (the hamiltonian's).
  KomarEquation(Grid& grid, const Fluid* fluid, const Puncture& puncture, std::shared_ptr<const Strength> strength);

  std::string name() const override { return "lapse"; }
  std::string unknown() const override { return eta_regular; }
  OuterBoundary boundary() const override;
  std::vector<std::string> coefficients() const override;
  void residual(const RelaxArgs& args, double* const* out) const override;
  void relax(const RelaxArgs& args) const override;

 private:
  Sources sources(int level) const;

  Grid& grid_;
  const Fluid* fluid_;
  const Puncture& puncture_;
  std::shared_ptr<const Strength> strength_;
  int eta_ = -1;
};

class KomarLapse final : public Lapse {
 public:
  explicit KomarLapse(std::shared_ptr<const Strength> strength) : strength_(std::move(strength)) {}
  void update(Grid& grid, int level) const override;
  std::string regular_part() const override { return eta_regular; }

 private:
  std::shared_ptr<const Strength> strength_;
};

}  // namespace bhnsid::lapse_komar
