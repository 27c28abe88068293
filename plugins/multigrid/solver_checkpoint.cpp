#include "bhnsid/core/errors.hpp"
#include "coarse_solver.hpp"
#include "solver.hpp"

namespace bhnsid::multigrid {

void FasSolver::save(core::CheckpointWriter& out) const {
  out.put_integer("warm", warm_ ? 1 : 0);
  out.put("tau", tau_);
  coarse_->save(out);
}

void FasSolver::restore(const core::CheckpointReader& in) {
  warm_ = in.integer("warm") != 0;
  const std::vector<double> tau = in.reals("tau");
  if (tau.size() != tau_.size())
    throw core::InputError("multigrid: the checkpoint solved another number of equations than this run");
  tau_ = tau;
  coarse_->restore(in);
}

}  // namespace bhnsid::multigrid
