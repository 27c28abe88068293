#pragma once
// Helpers of the sweep-order tests (core's vector sweep, mms's kernels): rough data that no
// smooth-field coincidence can hide behind, and a scoped OpenMP thread count.
#include <omp.h>

#include <cmath>
#include <cstddef>

namespace bhnsid::test {

/// A value per array index that varies from point to point; salt picks another sequence.
inline double pattern(std::size_t idx, int salt) { return std::sin(0.37 * static_cast<double>(idx) + 1.1 * salt); }

/// Sets the OpenMP thread count for its lifetime and restores the previous one.
class Threads {
 public:
  explicit Threads(int n) : saved_(omp_get_max_threads()) { omp_set_num_threads(n); }
  ~Threads() { omp_set_num_threads(saved_); }
  Threads(const Threads&) = delete;
  Threads& operator=(const Threads&) = delete;

 private:
  int saved_;
};

}  // namespace bhnsid::test
