#pragma once
// Analytic fields on a real grid, for tests that check a plugin against closed forms.
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::test {

/// Sets component `component` of field `name` to f(x, y, z) at every stored point of the finest level.
template <class F>
void fill(Grid& g, const char* name, int component, F&& f) {
  const Level& lv = g.finest();
  double* v = g.data(g.field_id(name), component, 0);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) v[lv.at(i, j, k)] = f(lv.x(i), lv.y(j), lv.z(k));
}

}  // namespace bhnsid::test
