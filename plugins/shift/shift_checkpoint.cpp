#include "bhnsid/core/errors.hpp"
#include "shift.hpp"

namespace bhnsid::shift {

void ShiftEquation::save(core::CheckpointWriter& out) const {
  out.put("puncture", {built_ ? 1.0 : 0.0, last_mass_, last_position_[0], last_position_[1], last_position_[2]});
  std::vector<std::int64_t> boxes = {last_finest_points_};
  for (const stencil::Box& b : held_box_) boxes.insert(boxes.end(), {b.i0, b.i1, b.j0, b.j1, b.k0, b.k1});
  out.put_integers("held_boxes", boxes);
  out.put_integers("nearest_levels", std::vector<std::int64_t>(last_nearest_levels_.begin(), last_nearest_levels_.end()));
  out.put("finest_dx", grid_.finest().dx);
}

void ShiftEquation::restore(const core::CheckpointReader& in) {
  const std::vector<double> p = in.reals("puncture");
  const std::vector<std::int64_t> boxes = in.integers("held_boxes");
  if (p.size() != 5 || boxes.empty() || (boxes.size() - 1) % 6 != 0)
    throw core::InputError("shift: the checkpoint's excision state is malformed");
  built_ = p[0] != 0;
  last_mass_ = p[1];
  last_position_ = {p[2], p[3], p[4]};
  last_finest_points_ = static_cast<int>(boxes[0]);
  held_box_.clear();
  for (std::size_t at = 1; at < boxes.size(); at += 6)
    held_box_.push_back(stencil::Box{static_cast<int>(boxes[at]), static_cast<int>(boxes[at + 1]),
                                     static_cast<int>(boxes[at + 2]), static_cast<int>(boxes[at + 3]),
                                     static_cast<int>(boxes[at + 4]), static_cast<int>(boxes[at + 5])});
  const std::vector<std::int64_t> nearest = in.integers("nearest_levels");
  last_nearest_levels_.assign(nearest.begin(), nearest.end());
}

void ShiftEquation::warm_start(const core::CheckpointReader& in) {
  // The held boxes are indices of the source's levels: only a run of this lattice can use them.
  if (in.real("finest_dx") == grid_.finest().dx) restore(in);
}

}  // namespace bhnsid::shift
