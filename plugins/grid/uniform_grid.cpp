#include "uniform_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::grid {

UniformGrid::UniformGrid(std::vector<Level> levels, Symmetry symmetry)
    : levels_(std::move(levels)), symmetry_(symmetry) {}

const Level& UniformGrid::level(int index) const {
  if (index < 0 || index >= num_levels())
    throw core::RunFailure(fmt::format("grid: level {} requested, the hierarchy has {}", index, num_levels()));
  return levels_[static_cast<std::size_t>(index)];
}

namespace {

// Time-odd fields flip under the y reflection because it is combined with time reversal
// (physics-notes §8); the z reflection alone is a pure spatial symmetry.
Parity parity_of(core::TensorKind kind, core::TimeParity time_parity) {
  Parity p;
  p.z = core::reflection_parity(kind, 2);
  p.y = core::reflection_parity(kind, 1) * (time_parity == core::TimeParity::odd ? -1 : 1);
  return p;
}

}  // namespace

int UniformGrid::add_field(const std::string& name, const std::vector<core::TensorKind>& components,
                           core::TimeParity time_parity, core::Storage storage) {
  if (components.empty()) throw core::RunFailure(fmt::format("grid: field '{}' registered without components", name));
  std::vector<Parity> parity;
  for (auto kind : components) parity.push_back(parity_of(kind, time_parity));
  if (auto it = field_ids_.find(name); it != field_ids_.end()) {
    const FieldInfo& old = fields_[static_cast<std::size_t>(it->second)].info;
    if (old.components != components || old.storage != storage ||
        (old.parity.size() && old.parity[0].y != parity[0].y))
      throw core::RunFailure(
          fmt::format("grid: field '{}' registered twice with different components or storage", name));
    return it->second;
  }
  Field f;
  f.info = FieldInfo{name, components, parity, storage};
  f.arrays.resize(components.size());
  for (auto& per_level : f.arrays) {
    per_level.resize(levels_.size());
    const std::size_t first = storage == core::Storage::coarse_levels ? 1 : 0;
    const std::size_t count = storage == core::Storage::finest_only ? 1 : levels_.size();
    for (std::size_t l = first; l < count; ++l) {
      const std::size_t bytes = levels_[l].size * sizeof(double);
      per_level[l] = arena_.allocate<double>(levels_[l].size);
      bytes_ += bytes;
    }
  }
  fields_.push_back(std::move(f));
  const int id = static_cast<int>(fields_.size()) - 1;
  field_ids_[name] = id;
  return id;
}

int UniformGrid::field_id(const std::string& name) const {
  auto it = field_ids_.find(name);
  if (it == field_ids_.end()) throw core::RunFailure(fmt::format("grid: no field named '{}' is registered", name));
  return it->second;
}

const UniformGrid::Field& UniformGrid::field(int id) const {
  if (id < 0 || id >= static_cast<int>(fields_.size()))
    throw core::RunFailure(fmt::format("grid: no field with id {}", id));
  return fields_[static_cast<std::size_t>(id)];
}

const FieldInfo& UniformGrid::field_info(int id) const { return field(id).info; }

const double* UniformGrid::data(int id, int component, int level) const {
  const Field& f = field(id);
  if (component < 0 || component >= static_cast<int>(f.arrays.size()) || level < 0 || level >= num_levels())
    throw core::RunFailure(fmt::format("grid: field '{}' has no component {} on level {}", f.info.name, component, level));
  const double* p = f.arrays[static_cast<std::size_t>(component)][static_cast<std::size_t>(level)].get();
  if (!p)
    throw core::RunFailure(fmt::format("grid: field '{}' is not stored on level {} ({})", f.info.name, level,
                                       core::to_string(f.info.storage)));
  return p;
}

double* UniformGrid::data(int id, int component, int level) {
  return const_cast<double*>(static_cast<const UniformGrid&>(*this).data(id, component, level));
}

void UniformGrid::fill_ghosts(double* values, Parity parity, int level_index) const {
  const Level& lv = level(level_index);
  fill_ghost_columns(values, parity, level_index, 0, lv.nx - 1, 0, lv.ny - 1);
}

void UniformGrid::fill_ghost_columns(double* values, Parity parity, int level_index, int i0, int i1, int j0,
                                     int j1) const {
  const Level& lv = level(level_index);
  if (!lv.z_symmetry) return;
  const double sign = parity.z;
  i0 = std::max(i0, 0), i1 = std::min(i1, lv.nx - 1), j0 = std::max(j0, 0), j1 = std::min(j1, lv.ny - 1);
  for (int j = j0; j <= j1; ++j) {
    double* ghost = values + lv.at(0, j, -1);
    const double* image = values + lv.at(0, j, 1);
    for (int i = i0; i <= i1; ++i) ghost[i] = sign * image[i];
  }
}

int UniformGrid::add_mask(const std::string& name, const ExcisionRegion& region) {
  for (std::size_t m = 0; m < masks_.size(); ++m) {
    if (masks_[m].name != name) continue;
    const ExcisionRegion& r = masks_[m].region;
    if (r.shape != region.shape || r.centre != region.centre || r.half_size != region.half_size)
      throw core::RunFailure(fmt::format("grid: mask '{}' registered twice with different regions", name));
    return static_cast<int>(m);
  }
  if (!(region.half_size > 0))
    throw core::RunFailure(fmt::format("grid: mask '{}' needs a positive half size, got {}", name, region.half_size));
  Mask mask{name, region, {}};
  for (const Level& lv : levels_) {
    ByteArray bytes = arena_.allocate<std::uint8_t>(lv.size);
    bytes_ += lv.size;
    // A small tolerance keeps points exactly on the region's surface inside on every level.
    const double tol = 1e-10 * lv.dx;
    auto inside = [&](double x, double y, double z) {
      const double dx = x - region.centre[0], dy = y - region.centre[1], dz = z - region.centre[2];
      if (region.shape == ExcisionRegion::Shape::cube)
        return std::fmax(std::fabs(dx), std::fmax(std::fabs(dy), std::fabs(dz))) <= region.half_size + tol;
      return std::sqrt(dx * dx + dy * dy + dz * dz) <= region.half_size + tol;
    };
    // The bytes are zero: only the region's bounding box (and, under equatorial symmetry, its
    // mirror image's, for the region stands for both) is visited.
    const double reach = region.half_size + tol;
    const auto& c = region.centre;
    const auto [ri, rj, rk] =
        lv.indices_near_box({c[0] - reach, c[1] - reach, c[2] - reach}, {c[0] + reach, c[1] + reach, c[2] + reach});
    for (int k = rk[0]; k <= rk[1]; ++k)
      for (int j = rj[0]; j <= rj[1]; ++j)
        for (int i = ri[0]; i <= ri[1]; ++i) {
          const double x = lv.x(i), y = lv.y(j), z = lv.z(k);
          const bool in = inside(x, y, z) || (lv.z_symmetry && inside(x, y, -z));
          bytes[static_cast<std::size_t>(lv.at(i, j, k))] = in ? 1 : 0;
        }
    mask.levels.push_back(std::move(bytes));
  }
  masks_.push_back(std::move(mask));
  return static_cast<int>(masks_.size()) - 1;
}

int UniformGrid::mask_id(const std::string& name) const {
  for (std::size_t m = 0; m < masks_.size(); ++m)
    if (masks_[m].name == name) return static_cast<int>(m);
  throw core::RunFailure(fmt::format("grid: no excision mask named '{}' is registered", name));
}

const std::uint8_t* UniformGrid::mask(int id, int level_index) const {
  if (id < 0 || id >= static_cast<int>(masks_.size()) || level_index < 0 || level_index >= num_levels())
    throw core::RunFailure(fmt::format("grid: no mask {} on level {}", id, level_index));
  return masks_[static_cast<std::size_t>(id)].levels[static_cast<std::size_t>(level_index)].get();
}

std::uint8_t* UniformGrid::mask_data(int id, int level_index) {
  return const_cast<std::uint8_t*>(std::as_const(*this).mask(id, level_index));  // the bytes are ours, allocated writable
}

}  // namespace bhnsid::grid
