#pragma once
// A manufactured problem on the grid: its fields, coefficients and equation services (SETUP),
// its initial data (INITIAL), its errors against the exact solution (ANALYSIS) and its line
// output (OUTPUT). The plugin's schedule calls these; the unit tests call them on a test grid.
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "problems.hpp"

namespace bhnsid::mms {

struct Settings {
  ProblemSpec problem;  ///< half_width is taken from the grid
  double excision_radius = 0;
  Vec3 excision_centre{};
  Vec3 robin_centre{};  ///< of the ball problem's Robin rows
  double initial_guess = 0;
};

struct Errors {
  double max = 0;  ///< max over stored points and components of |u - exact|
  double rms = 0;  ///< root mean square over the same
};

class Manufactured {
 public:
  static constexpr const char* mask_name = "mms.excision";

  /// Checks the problem against the grid (core::InputError naming the parameter), registers the
  /// unknown(s) and coefficient(s) on all levels and the excision mask, fills the coefficients on
  /// every box (the solver restricts them below) and their ghosts, and builds the equation service(s).
  Manufactured(Grid& grid, const Settings& settings);

  const ExactSolution& exact() const { return exact_; }
  /// The equation published as "equation.mms".
  std::shared_ptr<EllipticEquation> equation() const { return equations_[0]; }
  /// The coupled problem's second equation ("equation.mms_partner"); nullptr for the others.
  std::shared_ptr<EllipticEquation> partner() const { return equations_.size() > 1 ? equations_[1] : nullptr; }
  /// Grid field names of the unknowns, the partner's second.
  const std::vector<std::string>& unknowns() const { return unknowns_; }

  /// Every box (grid.boxes): exact values on the domain's faces (Dirichlet problems) and at
  /// excised points, the initial guess elsewhere (0 on z = 0 for components odd in z); ghosts filled.
  /// The coarser levels below the outermost box get theirs from the solver.
  void set_initial();
  /// Every stored point of every box to the exact solution; ghosts filled.
  void set_exact();
  /// Errors of unknown 0 (the equation's) or 1 (the partner's) on the composite grid: each box's
  /// points outside the finer box; rms weighted by volume (the L2 norm over the domain).
  Errors errors(int unknown) const;
  /// The x axis of the finest level: "# x  u  exact", or for several columns "# x  v_x  exact_v_x ..."
  /// (one pair per component and unknown).
  std::string line_table() const;

 private:
  /// Every stored point of every box to value_at(sampler of the box, component, i, j, k); ghosts filled.
  template <class Fn>
  void fill_boxes(int field, Fn&& value_at);

  Grid& grid_;
  Settings settings_;
  ExactSolution exact_;
  std::vector<std::string> unknowns_;
  std::vector<std::shared_ptr<EllipticEquation>> equations_;
  int mask_ = -1;
};

}  // namespace bhnsid::mms
