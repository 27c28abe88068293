#pragma once
// The EllipticEquation services of the manufactured problems. Each one only looks up its arrays
// on the requested level and hands them to a kernel (kernels/); all loops live there.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::mms {

/// What every manufactured equation shares: its name, fields, boundary and excision mask.
struct EquationSpec {
  std::string name;     ///< "mms" or "mms_partner"
  std::string unknown;  ///< "mms_u", "mms_v" or "mms_w"
  std::string source;   ///< the coefficient field s
  std::string mask;     ///< excision mask, empty for none
  OuterBoundary boundary;
};

class EquationBase : public EllipticEquation {
 public:
  EquationBase(Grid& grid, EquationSpec spec)
      : grid_(grid), spec_(std::move(spec)), u_(grid.field_id(spec_.unknown)), source_(grid.field_id(spec_.source)) {}
  std::string name() const override { return spec_.name; }
  std::string unknown() const override { return spec_.unknown; }
  OuterBoundary boundary() const override { return spec_.boundary; }
  std::string excision_mask() const override { return spec_.mask; }
  std::vector<std::string> coefficients() const override { return {spec_.source}; }

 protected:
  /// Refreshes the unknown's ghost plane on one level, for the kernels to call between colours.
  std::function<void()> mirror(int level) const {
    return [this, level] { grid_.fill_ghosts(u_, level); };
  }

  Grid& grid_;
  EquationSpec spec_;
  int u_, source_;
};

/// lap u + c u^5 + s (poisson and ball: c = 0, the linear kernels; nonlinear: c != 0).
class ScalarEquation final : public EquationBase {
 public:
  ScalarEquation(Grid& grid, EquationSpec spec, double c);
  void residual(const RelaxArgs& args, double* const* out) const override;
  void relax(const RelaxArgs& args) const override;

 private:
  double c_;
};

/// lap V^i + (1/3) d^i d_j V^j - kappa n^i n_j V^j + s^i, n = x / r_c.
class VectorEquation final : public EquationBase {
 public:
  VectorEquation(Grid& grid, EquationSpec spec, double kappa);
  void residual(const RelaxArgs& args, double* const* out) const override;
  void relax(const RelaxArgs& args) const override;

 private:
  double kappa_;
};

/// One equation of the coupled pair: lap own + coef other^power + s, power 1 or 3. Relaxes its own
/// unknown only; the other is the partner equation's unknown, read as it stands.
class CoupledEquation final : public EquationBase {
 public:
  CoupledEquation(Grid& grid, EquationSpec spec, std::string other, double coef, int power);
  void residual(const RelaxArgs& args, double* const* out) const override;
  void relax(const RelaxArgs& args) const override;

 private:
  int other_;
  double coef_;
  int power_;
};

}  // namespace bhnsid::mms
