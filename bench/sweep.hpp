#pragma once
// bhnsid-bench sweep: the cost of one of core's vector sweeps (interfaces/vector_sweep.hpp: the
// principal part lap V + (1/3) grad div V of three components plus a lower-order term) on one level
// of n intervals with equatorial symmetry, outside any solver: ns per point, in or out of cache.
// The lower-order term is none, the momentum constraint's (vacuum) or the minimal-distortion
// shift's with or without the puncture's analytic terms, on smooth stand-in coefficients: what
// each part of the equations' own kernels costs.
#include <string>

namespace bhnsid::bench {

/// Prints one JSON line per n in {32, 64, 128, 256} up to max_n; returns the exit status.
/// lower_term: "none", "momentum", "shift" or "shift-no-hole".
int vector_sweep(int max_n, int threads, const std::string& lower_term);

}  // namespace bhnsid::bench
