#pragma once
// bhnsid-bench sweep: the cost of one of core's vector sweeps (interfaces/vector_sweep.hpp, the
// principal part lap V + (1/3) grad div V of three components, no lower-order term) on one level
// of n intervals with equatorial symmetry, outside any solver: ns per point, in or out of cache.

namespace bhnsid::bench {

/// Prints one JSON line per n in {32, 64, 128, 256} up to max_n; returns the exit status.
int vector_sweep(int max_n, int threads);

}  // namespace bhnsid::bench
