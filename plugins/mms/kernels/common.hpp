#pragma once
// What every kernel shares: the ghost refresh handed in by the caller, and the compile-time
// variants of a sweep (FAS right-hand side present or not, held points or not), each its own loop
// so that the common case (no rhs on the finest level, no excision) tests nothing per point.
#include <functional>
#include <type_traits>

namespace bhnsid::mms::kernels {

/// Refreshes the ghost plane k = -1 of the unknown(s) being relaxed from plane 1 (equatorial
/// symmetry); the equation passes Grid::fill_ghosts, a test its own copy. Called once per sweep,
/// between the colours, so a std::function costs nothing that matters.
using Mirror = std::function<void()>;

/// Calls fn(std::bool_constant<has_rhs>{}, std::bool_constant<masked>{}).
template <class Fn>
void with_variants(bool has_rhs, bool masked, Fn&& fn) {
  if (has_rhs) {
    if (masked)
      fn(std::true_type{}, std::true_type{});
    else
      fn(std::true_type{}, std::false_type{});
  } else {
    if (masked)
      fn(std::false_type{}, std::true_type{});
    else
      fn(std::false_type{}, std::false_type{});
  }
}

}  // namespace bhnsid::mms::kernels
