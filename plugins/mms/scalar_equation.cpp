#include "equations.hpp"

#include "kernels/laplace.hpp"
#include "kernels/power5.hpp"

namespace bhnsid::mms {

ScalarEquation::ScalarEquation(Grid& grid, EquationSpec spec, double c) : EquationBase(grid, std::move(spec)), c_(c) {}

void ScalarEquation::residual(const RelaxArgs& args, double* const* out) const {
  const int l = args.level;
  const double* u = grid_.data(u_, 0, l);
  const double* s = grid_.data(source_, 0, l);
  const double* rhs = args.rhs ? args.rhs[0] : nullptr;
  // c = 0 takes the linear kernel, the one the benchmark times: no u^5 to pay for.
  if (c_ == 0)
    kernels::laplace_residual(grid_.level(l), u, s, rhs, args.fixed, out[0]);
  else
    kernels::power5_residual(grid_.level(l), u, c_, s, rhs, args.fixed, out[0]);
}

void ScalarEquation::relax(const RelaxArgs& args) const {
  const int l = args.level;
  double* u = grid_.data(u_, 0, l);
  const double* s = grid_.data(source_, 0, l);
  const double* rhs = args.rhs ? args.rhs[0] : nullptr;
  if (c_ == 0)
    kernels::laplace_relax(grid_.level(l), u, s, rhs, args.fixed, args.omega, mirror(l));
  else
    kernels::power5_relax(grid_.level(l), u, c_, s, rhs, args.fixed, args.omega, mirror(l));
}

}  // namespace bhnsid::mms
