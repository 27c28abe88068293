#include "equations.hpp"

#include "kernels/vector_laplace.hpp"

namespace bhnsid::mms {

VectorEquation::VectorEquation(Grid& grid, EquationSpec spec, double kappa)
    : EquationBase(grid, std::move(spec)), kappa_(kappa) {}

void VectorEquation::residual(const RelaxArgs& args, double* const* out) const {
  const int l = args.level;
  kernels::ConstComponents v, s;
  for (std::size_t c = 0; c < 3; ++c) {
    v[c] = grid_.data(u_, static_cast<int>(c), l);
    s[c] = grid_.data(source_, static_cast<int>(c), l);
  }
  kernels::vector_residual(grid_.level(l), v, s, kappa_, args.rhs, args.fixed, {out[0], out[1], out[2]});
}

void VectorEquation::relax(const RelaxArgs& args) const {
  const int l = args.level;
  kernels::Components v;
  kernels::ConstComponents s;
  for (std::size_t c = 0; c < 3; ++c) {
    v[c] = grid_.data(u_, static_cast<int>(c), l);
    s[c] = grid_.data(source_, static_cast<int>(c), l);
  }
  kernels::vector_relax(grid_.level(l), v, s, kappa_, args.rhs, args.fixed, args.omega, mirror(l));
}

}  // namespace bhnsid::mms
