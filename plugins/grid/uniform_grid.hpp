#pragma once
// The serial grid: one uniform vertex-centred level per multigrid depth, fields as aligned plain
// arrays, ghost points only on the symmetry plane, reductions that are the identity.
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/core/checkpoint.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "blocks.hpp"

namespace bhnsid::grid {

class UniformGrid final : public Grid {
 public:
  UniformGrid(std::vector<Level> levels, Symmetry symmetry);

  Symmetry symmetry() const override { return symmetry_; }
  int num_levels() const override { return static_cast<int>(levels_.size()); }
  const Level& level(int index) const override;

  int add_field(const std::string& name, const std::vector<core::TensorKind>& components,
                core::TimeParity time_parity, core::Storage storage) override;
  int field_id(const std::string& name) const override;
  bool has_field(const std::string& name) const override { return field_ids_.count(name) != 0; }
  const FieldInfo& field_info(int field) const override;
  int num_fields() const override { return static_cast<int>(fields_.size()); }
  double* data(int field, int component, int level) override;
  const double* data(int field, int component, int level) const override;

  using Grid::fill_ghosts;  // keep fill_ghosts(field, level) visible beside the override
  void fill_ghosts(double* values, Parity parity, int level) const override;
  using Grid::fill_ghost_columns;
  void fill_ghost_columns(double* values, Parity parity, int level, int i0, int i1, int j0, int j1) const override;

  int add_mask(const std::string& name, const ExcisionRegion& region) override;
  int mask_id(const std::string& name) const override;
  const std::uint8_t* mask(int mask, int level) const override;
  std::uint8_t* mask_data(int mask, int level) override;

  double global_sum(double local) const override { return local; }
  double global_max(double local) const override { return local; }

  double integrate(const double* values, Parity parity, int level) const override;
  double interpolate(const double* values, Parity parity, int level, std::array<double, 3> point) const override;
  std::vector<std::array<double, 2>> line_x(const double* values, int level) const override;

  /// Every array of every field and mask on every level, ghosts included (grid_checkpoint.cpp):
  /// the solver's warm state lives on the coarse levels too, so a resumed run continues bit for bit;
  /// and the finest level's n and dx ("lattice"), which a warm start compares with its own.
  void save(core::CheckpointWriter& out) const;
  /// The same arrays back; InputError (from the reader) when a field, level or size differs.
  void restore(const core::CheckpointReader& in);
  /// `bhnsid run --warm-start`: restore() from a run of this lattice; from the next coarser one
  /// (n half, dx twice), each field's finest level interpolated (second order) and its coarse
  /// levels shifted down by one; the masks stay as SETUP made them.
  void warm_start(const core::CheckpointReader& in);

  /// Bytes held by all fields and masks, for the log.
  std::size_t bytes_allocated() const { return bytes_; }

 private:
  struct Field {
    FieldInfo info;
    std::vector<std::vector<DoubleArray>> arrays;  // [component][level]; coarse levels empty for finest_only
  };
  struct Mask {
    std::string name;
    ExcisionRegion region;
    std::vector<ByteArray> levels;
  };
  const Field& field(int id) const;

  std::vector<Level> levels_;
  Symmetry symmetry_;
  BlockArena arena_;          // before the fields and masks: destroyed after the arrays it holds
  std::deque<Field> fields_;  // a deque: references from field_info() survive add_field()
  std::map<std::string, int> field_ids_;
  std::vector<Mask> masks_;
  std::size_t bytes_ = 0;
};

}  // namespace bhnsid::grid
