#pragma once
// The smooth fill of a held region (the shift's excision cube): its grid points get the discrete
// harmonic function (7-point Laplacian = 0) whose Dirichlet data are the stored values on the
// first points outside. reader/README.md says why and what it reproduces.
#include <string>
#include <vector>

#include "data_file.hpp"

namespace bhnsid::reader {

/// Whether the physical point x is in the region, or (equatorial symmetry) its mirror is: the
/// region is used together with its reflection, because the stored half cannot tell them apart.
/// Inclusive by a tolerance of 1e-9 dx, so a point the solver held on the boundary is never used
/// as boundary data.
bool in_held_region(const HeldRegion& r, const Grid& g, double x, double y, double z);

/// Replaces the stored values inside `r` by the harmonic fill and returns how many stored points
/// changed. Throws ERR_FORMAT if the region leaves no point outside it to take data from.
std::size_t harmonic_fill(const Grid& g, const HeldRegion& r, int parity, std::vector<double>& values,
                          const std::string& path);

}  // namespace bhnsid::reader
