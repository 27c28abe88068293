#pragma once
// The benchmarks' timing loop: one warm-up call (first touch, caches), then the best of 5 rounds of
// `reps` calls, in seconds per call.
#include <algorithm>
#include <chrono>

namespace bhnsid::bench {

template <class Fn>
double best_seconds(int reps, Fn&& fn) {
  fn();
  double best = 1e300;
  for (int round = 0; round < 5; ++round) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) fn();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / reps);
  }
  return best;
}

}  // namespace bhnsid::bench
