#pragma once
// bhnsid-bench robin: the cost of the multigrid's outer-boundary (Robin) rows outside any solver,
// for the boosted puncture's level at n intervals (equatorial symmetry, r_c = 20): one relaxation
// and one residual of the two row sets the eight equations use, chi and eta about the puncture
// (u_inf = 1) and the six components of W and beta about the origin (u_inf = 0). They are about a
// seventh of the eight equations' run (docs/performance.md).
namespace bhnsid::bench {

/// Prints one JSON line; returns the exit status.
int robin_rows(int n, int threads);

}  // namespace bhnsid::bench
