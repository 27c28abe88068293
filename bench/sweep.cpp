#include "sweep.hpp"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "bhnsid/interfaces/vector_sweep.hpp"
#include "test_level.hpp"

namespace bhnsid::bench {

namespace {

struct NoLowerTerm {
  stencil::Triple at(std::ptrdiff_t, int, const stencil::Rows&, const stencil::Rows&, const stencil::Rows&) const {
    return {0.0, 0.0, 0.0};
  }
};

}  // namespace

int vector_sweep(int max_n, int threads) {
  if (max_n < 32 || (max_n & (max_n - 1)) != 0) {
    std::cerr << "bhnsid-bench sweep: --n must be a power of 2, at least 32, got " << max_n << "\n";
    return 2;
  }
  omp_set_num_threads(threads);
  for (int n = 32; n <= max_n; n *= 2) {
    const Level lv = test::make_level(n, 1.0 / n, true);
    std::vector<double> v[3];
    for (auto& a : v) {
      a.resize(lv.size);
      for (std::size_t i = 0; i < lv.size; ++i) a[i] = std::sin(0.1 * static_cast<double>(i));
    }
    const stencil::Components c{v[0].data(), v[1].data(), v[2].data()};
    auto sweep = [&] { stencil::vector_relax_any(lv, c, nullptr, nullptr, 1.15, [] {}, NoLowerTerm{}); };
    sweep();  // first touch
    // About 0.2 s of sweeps per n; the best of 5 rounds.
    const double points = static_cast<double>(lv.nx - 2) * (lv.ny - 2) * (lv.nz - 1);
    const int reps = std::max(1, static_cast<int>(2e6 / points));
    double best = 1e300;
    for (int round = 0; round < 5; ++round) {
      const auto start = std::chrono::steady_clock::now();
      for (int r = 0; r < reps; ++r) sweep();
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / reps);
    }
    const nlohmann::json out = {{"case", "vector_sweep"},
                                {"n", n},
                                {"threads", threads},
                                {"sweep_seconds", best},
                                {"ns_per_point", best / points * 1e9},
                                {"megabytes", 3.0 * static_cast<double>(lv.size) * 8 / 1e6}};
    std::cout << out.dump() << std::endl;
  }
  return 0;
}

}  // namespace bhnsid::bench
