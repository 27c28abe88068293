#include "equations.hpp"

#include "kernels/coupled.hpp"

namespace bhnsid::mms {

CoupledEquation::CoupledEquation(Grid& grid, EquationSpec spec, std::string other, double coef, int power)
    : EquationBase(grid, std::move(spec)), other_(grid.field_id(other)), coef_(coef), power_(power) {}

void CoupledEquation::residual(const RelaxArgs& args, double* const* out) const {
  const int l = args.level;
  kernels::coupled_residual(grid_.level(l), grid_.data(u_, 0, l), grid_.data(other_, 0, l), coef_, power_,
                            grid_.data(source_, 0, l), args.rhs ? args.rhs[0] : nullptr, args.fixed, out[0]);
}

void CoupledEquation::relax(const RelaxArgs& args) const {
  const int l = args.level;
  kernels::coupled_relax(grid_.level(l), grid_.data(u_, 0, l), grid_.data(other_, 0, l), coef_, power_,
                         grid_.data(source_, 0, l), args.rhs ? args.rhs[0] : nullptr, args.fixed, args.omega,
                         mirror(l));
}

}  // namespace bhnsid::mms
