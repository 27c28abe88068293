#pragma once
// The grid plugin's serial grid for unit tests of other plugins (their uses.cmake names the grid
// plugin's sources): n intervals of dx per side with equatorial symmetry, and the scalar fields the
// test names registered on every level.
#include <initializer_list>
#include <memory>

#include "hierarchy.hpp"
#include "uniform_grid.hpp"

namespace bhnsid::test {

inline std::unique_ptr<grid::UniformGrid> equatorial_grid(int n, double dx, std::initializer_list<const char*> scalars) {
  grid::HierarchySpec spec;
  spec.n = n;
  spec.dx = dx;
  spec.symmetry = Symmetry::equatorial;
  auto g = std::make_unique<grid::UniformGrid>(grid::build_hierarchy(spec), Symmetry::equatorial);
  for (const char* name : scalars) static_cast<Grid&>(*g).add_field(name, {core::TensorKind::scalar});
  return g;
}

}  // namespace bhnsid::test
