#include <fmt/format.h>

#include <cmath>

#include "bhnsid/core/errors.hpp"
#include "uniform_grid.hpp"

namespace bhnsid::grid {

namespace {

std::string field_entry(const std::string& field, std::size_t component, std::size_t level) {
  return fmt::format("field/{}/{}/{}", field, component, level);
}

// Trilinear prolongation of vertex-centred values: a fine point on a coarse one takes its value,
// one between two (four, eight) the mean of those. Second order, and monotone, so a density stays
// >= 0 at the star's surface; the outer iteration's first steps remove the O(dx^2) difference.
void prolong_linear(const double* coarse, const Level& cl, double* fine, const Level& fl) {
#pragma omp parallel for schedule(static)
  for (int k = 0; k < fl.nz; ++k) {
    const int k0 = k / 2, k1 = k0 + k % 2;
    for (int j = 0; j < fl.ny; ++j) {
      const int j0 = j / 2, j1 = j0 + j % 2;
      const double* c00 = coarse + cl.at(0, j0, k0);
      const double* c01 = coarse + cl.at(0, j0, k1);
      const double* c10 = coarse + cl.at(0, j1, k0);
      const double* c11 = coarse + cl.at(0, j1, k1);
      double* out = fine + fl.at(0, j, k);
      for (int i = 0; i < fl.nx; ++i) {
        const int i0 = i / 2, i1 = i0 + i % 2;
        out[i] = 0.125 * (c00[i0] + c00[i1] + c01[i0] + c01[i1] + c10[i0] + c10[i1] + c11[i0] + c11[i1]);
      }
    }
  }
}

}  // namespace

void UniformGrid::save(core::CheckpointWriter& out) const {
  for (const Field& f : fields_)
    for (std::size_t c = 0; c < f.arrays.size(); ++c)
      for (std::size_t l = 0; l < f.arrays[c].size(); ++l)
        if (f.arrays[c][l]) out.put(field_entry(f.info.name, c, l), f.arrays[c][l].get(), levels_[l].size);
  for (const Mask& m : masks_) {
    const double region[4] = {m.region.centre[0], m.region.centre[1], m.region.centre[2], m.region.half_size};
    out.put(fmt::format("mask/{}/region", m.name), region, 4);
    for (std::size_t l = 0; l < m.levels.size(); ++l)
      out.put_bytes(fmt::format("mask/{}/{}", m.name, l), m.levels[l].get(), levels_[l].size);
  }
  out.put("lattice", std::vector<double>{static_cast<double>(levels_[0].n), levels_[0].dx});
  out.put("boxes", std::vector<double>{static_cast<double>(num_boxes())});
}

void UniformGrid::restore(const core::CheckpointReader& in) {
  for (Field& f : fields_)
    for (std::size_t c = 0; c < f.arrays.size(); ++c)
      for (std::size_t l = 0; l < f.arrays[c].size(); ++l)
        if (f.arrays[c][l]) in.get(field_entry(f.info.name, c, l), f.arrays[c][l].get(), levels_[l].size);
  for (Mask& m : masks_) {
    double region[4];
    in.get(fmt::format("mask/{}/region", m.name), region, 4);
    m.region.centre = {region[0], region[1], region[2]};
    m.region.half_size = region[3];
    for (std::size_t l = 0; l < m.levels.size(); ++l)
      in.get_bytes(fmt::format("mask/{}/{}", m.name, l), m.levels[l].get(), levels_[l].size);
  }
}

void UniformGrid::warm_start(const core::CheckpointReader& in) {
  const std::vector<double> lattice = in.reals("lattice");
  if (lattice.size() != 2) throw core::InputError("grid: the checkpoint's lattice entry is malformed");
  const Level& fine = levels_[0];
  // Checkpoints written before nested boxes existed hold a single cube.
  const int their_boxes = in.has("boxes") ? static_cast<int>(in.reals("boxes").at(0)) : 1;
  if (their_boxes != num_boxes())
    throw core::InputError(fmt::format("grid: the checkpoint has grid.boxes = {}, this run {}", their_boxes, num_boxes()));
  if (static_cast<int>(lattice[0]) == fine.n && lattice[1] == fine.dx) return restore(in);
  if (num_boxes() > 1)
    throw core::InputError(fmt::format(
        "grid: a warm start from the next coarser lattice (n = {}, dx = {}) is not available with grid.boxes = {} yet; "
        "start from the same lattice or from a cold start",
        lattice[0], lattice[1], num_boxes()));
  // The next coarser run of the same cube (the core let only that through): its finest level is
  // our level 1, its level l our level l + 1.
  if (static_cast<int>(lattice[0]) * 2 != fine.n || std::fabs(lattice[1] - 2 * fine.dx) > 1e-12 * fine.dx ||
      levels_.size() < 2)
    throw core::InputError(fmt::format("grid: the checkpoint's lattice (n = {}, dx = {}) is neither this run's (n = {}, "
                                       "dx = {}) nor the next coarser one{}",
                                       lattice[0], lattice[1], fine.n, fine.dx,
                                       levels_.size() < 2 ? " on a hierarchy of two or more levels" : ""));
  const Level& coarse = levels_[1];
  std::vector<double> theirs;
  for (Field& f : fields_)
    for (std::size_t c = 0; c < f.arrays.size(); ++c) {
      const std::string finest = field_entry(f.info.name, c, 0);
      if (!in.has(finest)) continue;  // a field the source did not have keeps INITIAL's values
      theirs = in.reals(finest);
      if (theirs.size() != coarse.size)
        throw core::InputError(fmt::format("grid: the checkpoint's field {} holds {} values, the next coarser level {}",
                                           f.info.name, theirs.size(), coarse.size));
      prolong_linear(theirs.data(), coarse, f.arrays[c][0].get(), fine);
      fill_ghosts(f.arrays[c][0].get(), f.info.parity[c], 0);
      // The coarse levels as the source left them (its FAS state is their warm state too).
      for (std::size_t l = 1; l < f.arrays[c].size(); ++l)
        if (f.arrays[c][l] && in.has(field_entry(f.info.name, c, l - 1)))
          in.get(field_entry(f.info.name, c, l - 1), f.arrays[c][l].get(), levels_[l].size);
    }
  // The masks stay as SETUP drew them on this lattice; the shift rebuilds its excision with them.
}

}  // namespace bhnsid::grid
