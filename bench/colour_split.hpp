#pragma once
// bhnsid-bench colour-split: what the vector sweeps would cost with each colour stored apart. The
// vector sweeps are the eight-equation solve's largest cost (docs/performance.md) and run each
// colour at stride 2 in the shared layout. This runs core's sweep of the principal part (no
// lower-order term) beside a sweep of the same operator on a colour-split copy of the same
// unknowns (for each row, its colour-0 points contiguous in one array and its colour-1 points in
// another, so that every access of a colour pass is unit-stride), checks that both give the same
// values, and prints both times. An experiment for the layout proposed in docs/performance.md,
// not a kernel of the solver.
namespace bhnsid::bench {

/// Prints one JSON line for n (a power of 2 >= 32); returns the exit status (1 if the two sweeps
/// disagree).
int colour_split_sweep(int n, int threads);

}  // namespace bhnsid::bench
