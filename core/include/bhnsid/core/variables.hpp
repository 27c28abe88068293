#pragma once
// Grid variables as plugins declare them. The core only records them; the grid plugin allocates
// storage and derives each variable's parity under reflections from its tensor kind.
#include <string>

namespace bhnsid::core {

enum class TensorKind {
  scalar,
  vector_x, vector_y, vector_z,
  tensor_xx, tensor_xy, tensor_xz, tensor_yy, tensor_yz, tensor_zz,
};

/// Behaviour under time reversal: the shift, momenta and fluid velocity are odd (physics-notes §8).
enum class TimeParity { even, odd };

/// Which levels of the multigrid hierarchy hold a variable: solver scratch such as FAS right-hand
/// sides lives on the coarse levels only, diagnostics on the finest only.
enum class Storage { all_levels, finest_only, coarse_levels };

struct VariableSpec {
  std::string name;
  TensorKind kind = TensorKind::scalar;
  TimeParity time_parity = TimeParity::even;
  Storage storage = Storage::all_levels;
  std::string doc;
  std::string plugin;  ///< filled in by the core
};

const char* to_string(TensorKind kind);
const char* to_string(Storage storage);

/// Parity (+1 or -1) of a component under the reflection x_axis -> -x_axis (axis 0, 1, 2), from the
/// number of its indices along that axis; time-odd fields flip once more for reflections that also
/// reverse the orbital motion, which the grid decides, not this function.
int reflection_parity(TensorKind kind, int axis);

}  // namespace bhnsid::core
