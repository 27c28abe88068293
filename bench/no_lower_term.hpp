#pragma once
// The empty lower-order term: core's vector sweep of the principal part alone.
#include <cstddef>

#include "bhnsid/interfaces/vector_sweep.hpp"

namespace bhnsid::bench {

struct NoLowerTerm {
  stencil::Triple at(std::ptrdiff_t, std::ptrdiff_t, const stencil::Rows&, const stencil::Rows&, const stencil::Rows&) const {
    return {0.0, 0.0, 0.0};
  }
};

}  // namespace bhnsid::bench
