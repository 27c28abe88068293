#include "bhnsid/core/errors.hpp"
#include "coarse_solver.hpp"
#include "solver.hpp"

namespace bhnsid::multigrid {

void FasSolver::save(core::CheckpointWriter& out) const {
  out.put_integer("warm", warm_ ? 1 : 0);
  out.put("tau", tau_);
  coarse_->save(out);
}

// A resume (or a warm start on this lattice) takes what a warm start from a coarser run takes, and
// the coarsest level's Jacobian, which goes with the masks the grid restores with it.
void FasSolver::restore(const core::CheckpointReader& in) {
  warm_start_from_coarser(in);
  coarse_->restore(in);
}

void FasSolver::warm_start_from_coarser(const core::CheckpointReader& in) {
  warm_ = in.integer("warm") != 0;
  const std::vector<double> tau = in.reals("tau");
  if (tau.size() != tau_.size())
    throw core::InputError("multigrid: the checkpoint solved another number of equations than this run");
  tau_ = tau;
}

}  // namespace bhnsid::multigrid
