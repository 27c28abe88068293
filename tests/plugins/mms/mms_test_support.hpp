#pragma once
// Shared pieces of the mms unit tests: the plugin's default settings per problem, the residual of
// an equation as the solver would take it, and relaxation as the solver drives it.
#include <algorithm>
#include <cmath>
#include <vector>

#include "manufactured.hpp"
#include "mms_test_grid.hpp"

namespace bhnsid::mms::test {

/// The plugin's parameter defaults (plugin.cpp) for one problem.
inline Settings defaults(Problem problem) {
  Settings s;
  s.problem.problem = problem;
  s.problem.nonlinear_c = -1.0;
  s.problem.vector_coupling = 0.0;
  s.problem.ball_mass = 1.0;
  s.problem.ball_radius = 0.5;
  s.problem.ball_centre = {0.1, 0, 0};
  s.problem.coupled_a = 1.0;
  s.problem.coupled_b = -1.0;
  return s;
}

/// Residual arrays of one equation on the grid's level (one per component).
struct Residual {
  std::vector<std::vector<double>> values;
  double max_interior = 0;  ///< max over interior points and components of |rhs - L(u)|
};

inline Residual residual_of(const EllipticEquation& eq, MemoryGrid& grid, const RelaxArgs& args = {}) {
  const Level& lv = grid.finest();
  const int ncomp = static_cast<int>(grid.field_info(grid.field_id(eq.unknown())).components.size());
  Residual r;
  r.values.assign(static_cast<std::size_t>(ncomp), std::vector<double>(lv.size, 0.0));
  std::vector<double*> out;
  for (auto& v : r.values) out.push_back(v.data());
  eq.residual(args, out.data());
  for (const auto& v : r.values)
    for (int k = lv.k_begin(); k < lv.nz - 1; ++k)
      for (int j = 1; j < lv.ny - 1; ++j)
        for (int i = 1; i < lv.nx - 1; ++i) r.max_interior = std::max(r.max_interior, std::fabs(v[lv.at(i, j, k)]));
  return r;
}

/// One sweep of every equation, each followed by the ghost refresh the solver does after relax().
inline void sweep(const std::vector<EllipticEquation*>& equations, MemoryGrid& grid, const RelaxArgs& args = {}) {
  for (EllipticEquation* eq : equations) {
    eq->relax(args);
    grid.fill_ghosts(grid.field_id(eq->unknown()), 0);
  }
}

/// Every stored point not on an outer face to `guess` (components odd in z stay 0 on z = 0), faces
/// kept: a Dirichlet start from the exact solution's boundary values.
inline void interior_to(MemoryGrid& grid, const std::string& field_name, double guess) {
  const Level& lv = grid.finest();
  const int field = grid.field_id(field_name);
  const FieldInfo& info = grid.field_info(field);
  for (int c = 0; c < static_cast<int>(info.components.size()); ++c) {
    double* u = grid.data(field, c, 0);
    const bool odd = info.parity[static_cast<std::size_t>(c)].z < 0;
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j)
        for (int i = 0; i < lv.nx; ++i)
          if (!lv.on_outer_face(i, j, k)) u[lv.at(i, j, k)] = (odd && lv.z_symmetry && k == 0) ? 0.0 : guess;
  }
  grid.fill_ghosts(field, 0);
}

inline std::vector<EllipticEquation*> equations_of(const Manufactured& m) {
  std::vector<EllipticEquation*> eqs{m.equation().get()};
  if (m.partner()) eqs.push_back(m.partner().get());
  return eqs;
}

}  // namespace bhnsid::mms::test
