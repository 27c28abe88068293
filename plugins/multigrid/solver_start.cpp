// The copy of a solve's start that lets the outer loop undo a failed solve (the core's RETREAT):
// in double precision, so that held points and Dirichlet faces come back exactly.
#include <algorithm>

#include "solver.hpp"

namespace bhnsid::multigrid {

void FasSolver::keep_start() {
  const Level& lv = grid_.level(0);
  std::size_t total = 0;
  for (const Slot& s : slots_) total += static_cast<std::size_t>(s.ncomp) * lv.size;
  start_.resize(total);
  double* out = start_.data();
  for (const Slot& s : slots_)
    for (int c = 0; c < s.ncomp; ++c) {
      const double* u = grid_.data(s.u, c, 0);
      out = std::copy(u, u + lv.size, out);
    }
  start_warm_ = warm_;
  has_start_ = true;
}

bool FasSolver::restore_start() {
  if (!has_start_) return false;
  const Level& lv = grid_.level(0);
  const double* in = start_.data();
  for (const Slot& s : slots_)
    for (int c = 0; c < s.ncomp; ++c) {
      std::copy(in, in + lv.size, grid_.data(s.u, c, 0));
      in += lv.size;
    }
  fill_ghosts(0);
  warm_ = start_warm_;
  return true;
}

}  // namespace bhnsid::multigrid
