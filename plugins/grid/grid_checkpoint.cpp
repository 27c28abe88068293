#include <fmt/format.h>

#include "uniform_grid.hpp"

namespace bhnsid::grid {

void UniformGrid::save(core::CheckpointWriter& out) const {
  for (const Field& f : fields_)
    for (std::size_t c = 0; c < f.arrays.size(); ++c)
      for (std::size_t l = 0; l < f.arrays[c].size(); ++l)
        if (f.arrays[c][l]) out.put(fmt::format("field/{}/{}/{}", f.info.name, c, l), f.arrays[c][l].get(), levels_[l].size);
  for (const Mask& m : masks_) {
    const double region[4] = {m.region.centre[0], m.region.centre[1], m.region.centre[2], m.region.half_size};
    out.put(fmt::format("mask/{}/region", m.name), region, 4);
    for (std::size_t l = 0; l < m.levels.size(); ++l)
      out.put_bytes(fmt::format("mask/{}/{}", m.name, l), m.levels[l].get(), levels_[l].size);
  }
}

void UniformGrid::restore(const core::CheckpointReader& in) {
  for (Field& f : fields_)
    for (std::size_t c = 0; c < f.arrays.size(); ++c)
      for (std::size_t l = 0; l < f.arrays[c].size(); ++l)
        if (f.arrays[c][l]) in.get(fmt::format("field/{}/{}/{}", f.info.name, c, l), f.arrays[c][l].get(), levels_[l].size);
  for (Mask& m : masks_) {
    double region[4];
    in.get(fmt::format("mask/{}/region", m.name), region, 4);
    m.region.centre = {region[0], region[1], region[2]};
    m.region.half_size = region[3];
    for (std::size_t l = 0; l < m.levels.size(); ++l)
      in.get_bytes(fmt::format("mask/{}/{}", m.name, l), m.levels[l].get(), levels_[l].size);
  }
}

}  // namespace bhnsid::grid
