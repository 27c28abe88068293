#pragma once
// A one-level grid for the mms unit tests, so that they need not link the grid plugin: the level
// is laid out exactly as plugins/grid/hierarchy.cpp make_level does (one ghost layer, x
// contiguous), fields are plain vectors, and fill_ghosts/add_mask/line_x behave like the grid
// plugin's. Sampling functions the mms plugin never calls throw.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "bhnsid/core/variables.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "test_level.hpp"

namespace bhnsid::mms::test {

using bhnsid::test::make_level;

/// Mirror of the ghost plane k = -1 from k = 1 with the given sign, as UniformGrid::fill_ghosts.
inline void mirror_plane(const Level& lv, double* values, double sign) {
  if (!lv.z_symmetry) return;
  for (int j = 0; j < lv.ny; ++j)
    for (int i = 0; i < lv.nx; ++i) values[lv.at(i, j, -1)] = sign * values[lv.at(i, j, 1)];
}

class MemoryGrid final : public Grid {
 public:
  MemoryGrid(int n, double dx, bool z_symmetry) : level_(make_level(n, dx, z_symmetry)) {}

  Symmetry symmetry() const override { return level_.z_symmetry ? Symmetry::equatorial : Symmetry::none; }
  int num_levels() const override { return 1; }
  const Level& level(int index) const override {
    if (index != 0) throw std::out_of_range("MemoryGrid has one level");
    return level_;
  }

  int add_field(const std::string& name, const std::vector<core::TensorKind>& components, core::TimeParity,
                core::Storage storage) override {
    if (auto it = ids_.find(name); it != ids_.end()) return it->second;
    Field f;
    f.info.name = name;
    f.info.components = components;
    f.info.storage = storage;
    for (auto kind : components) f.info.parity.push_back(Parity{core::reflection_parity(kind, 2), 1});
    f.data.assign(components.size(), std::vector<double>(level_.size, 0.0));
    fields_.push_back(std::move(f));
    ids_[name] = static_cast<int>(fields_.size()) - 1;
    return ids_[name];
  }
  int field_id(const std::string& name) const override {
    auto it = ids_.find(name);
    if (it == ids_.end()) throw std::out_of_range("MemoryGrid: no field " + name);
    return it->second;
  }
  bool has_field(const std::string& name) const override { return ids_.count(name) != 0; }
  const FieldInfo& field_info(int field) const override { return fields_.at(static_cast<std::size_t>(field)).info; }
  int num_fields() const override { return static_cast<int>(fields_.size()); }
  double* data(int field, int component, int level) override {
    return const_cast<double*>(static_cast<const MemoryGrid&>(*this).data(field, component, level));
  }
  const double* data(int field, int component, int level) const override {
    if (level != 0) throw std::out_of_range("MemoryGrid has one level");
    return fields_.at(static_cast<std::size_t>(field)).data.at(static_cast<std::size_t>(component)).data();
  }

  void fill_ghosts(double* values, Parity parity, int) const override { mirror_plane(level_, values, parity.z); }
  using Grid::fill_ghosts;

  int add_mask(const std::string& name, const ExcisionRegion& region) override {
    for (std::size_t m = 0; m < masks_.size(); ++m)
      if (mask_names_[m] == name) return static_cast<int>(m);
    std::vector<std::uint8_t> bytes(level_.size, 0);
    const Level& lv = level_;
    auto inside = [&](double x, double y, double z) {
      const double dx = x - region.centre[0], dy = y - region.centre[1], dz = z - region.centre[2];
      if (region.shape == ExcisionRegion::Shape::cube)
        return std::max({std::fabs(dx), std::fabs(dy), std::fabs(dz)}) <= region.half_size + 1e-10 * lv.dx;
      return std::sqrt(dx * dx + dy * dy + dz * dz) <= region.half_size + 1e-10 * lv.dx;
    };
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j)
        for (int i = 0; i < lv.nx; ++i) {
          const bool in = inside(lv.x(i), lv.y(j), lv.z(k)) || (lv.z_symmetry && inside(lv.x(i), lv.y(j), -lv.z(k)));
          bytes[static_cast<std::size_t>(lv.at(i, j, k))] = in ? 1 : 0;
        }
    masks_.push_back(std::move(bytes));
    mask_names_.push_back(name);
    return static_cast<int>(masks_.size()) - 1;
  }
  int mask_id(const std::string& name) const override {
    for (std::size_t m = 0; m < masks_.size(); ++m)
      if (mask_names_[m] == name) return static_cast<int>(m);
    throw std::out_of_range("MemoryGrid: no mask " + name);
  }
  const std::uint8_t* mask(int mask, int) const override { return masks_.at(static_cast<std::size_t>(mask)).data(); }
  std::uint8_t* mask_data(int mask, int) override { return masks_.at(static_cast<std::size_t>(mask)).data(); }

  double global_sum(double local) const override { return local; }
  double global_max(double local) const override { return local; }

  double integrate(const double*, Parity, int) const override { throw std::logic_error("MemoryGrid: no integrate"); }
  double interpolate(const double*, Parity, int, std::array<double, 3>) const override {
    throw std::logic_error("MemoryGrid: no interpolate");
  }
  std::vector<std::array<double, 2>> line_x(const double* values, int) const override {
    const Level& lv = level_;
    const int j = lv.n / 2, k = lv.z_symmetry ? 0 : lv.n / 2;
    std::vector<std::array<double, 2>> line;
    for (int i = 0; i < lv.nx; ++i) line.push_back({lv.x(i), values[lv.at(i, j, k)]});
    return line;
  }

 private:
  struct Field {
    FieldInfo info;
    std::vector<std::vector<double>> data;  // [component]
  };
  Level level_;
  std::vector<Field> fields_;
  std::map<std::string, int> ids_;
  std::vector<std::vector<std::uint8_t>> masks_;
  std::vector<std::string> mask_names_;
};

}  // namespace bhnsid::mms::test
