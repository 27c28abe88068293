#pragma once
// Tensor-product Lagrange interpolation on the stored grid: `order` points per axis (even), the
// stencil centred on the cell that holds the point and shifted inwards at the grid's edges; under
// equatorial symmetry the z stencil runs below z = 0 through the field's parity.
#include <array>
#include <cstddef>

#include "data_file.hpp"

namespace bhnsid::reader {

constexpr int max_order = 8;

struct Options {
  int order = 4;
  int out_of_grid = 0;  // BHNSID_READER_OUTSIDE_*
};

/// Throws ERR_ARGUMENT unless order is 2, 4, 6 or 8, the policy is known and the grid has at
/// least `order` points along every axis.
void check_options(const Grid& g, const Options& o);

struct Stencil {
  int order = 0;
  std::array<int, 3> start{};  // first index per axis (z may be negative: mirrored)
  std::array<std::array<double, max_order>, 3> w{};
  /// The physical point the stencil is for: the one asked, or where the clamp policy moved it.
  std::array<double, 3> point{};
  /// The point lies outside the box and the extrapolate policy evaluates the edge polynomial there.
  bool extrapolated = false;
};

/// The stencil at physical point (x, y, z) under the out-of-grid policy; throws ERR_OUTSIDE naming
/// point number `index` when the policy is an error.
Stencil stencil_at(const Grid& g, const Options& o, double x, double y, double z, std::size_t index);

/// sum_c w_z[c] sum_b w_y[b] sum_a w_x[a] f(start + (a, b, c)), in that order (the Python module
/// sums in the same order).
double interpolate(const Grid& g, const Field& f, const Stencil& s);

}  // namespace bhnsid::reader
