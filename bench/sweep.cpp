#include "sweep.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "bhnsid/interfaces/vector_sweep.hpp"
#include "no_lower_term.hpp"
#include "momentum/kernels.hpp"
#include "shift/kernels.hpp"
#include "test_level.hpp"
#include "timing.hpp"

namespace bhnsid::bench {

namespace {

// Smooth stand-ins for the coefficient fields the lower-order terms read: positive chi and eta of
// order 1 and an Ahat of order 1e-2, varying on a few cells so that no term is constant.
struct Coefficients {
  std::vector<double> chi, eta, ahat[6];
  explicit Coefficients(const Level& lv) : chi(lv.size), eta(lv.size) {
    for (auto& a : ahat) a.resize(lv.size);
    for (std::size_t i = 0; i < lv.size; ++i) {
      const double t = static_cast<double>(i);
      chi[i] = 1.0 + 0.01 * std::sin(0.3 * t);
      eta[i] = 1.0 + 0.01 * std::cos(0.2 * t);
      for (int c = 0; c < 6; ++c) ahat[c][i] = 0.01 * std::cos(0.1 * t + c);
    }
  }
};

template <class Lower>
double best_sweep_seconds(const Level& lv, const stencil::Components& v, const std::uint8_t* fixed, const Lower& lower,
                          int reps) {
  return best_seconds(reps, [&] { stencil::vector_relax_any(lv, v, nullptr, fixed, 1.15, [] {}, lower); });
}

}  // namespace

int vector_sweep(int max_n, int threads, const std::string& lower_term) {
  if (max_n < 32 || (max_n & (max_n - 1)) != 0) {
    std::cerr << "bhnsid-bench sweep: --n must be a power of 2, at least 32, got " << max_n << "\n";
    return 2;
  }
  omp_set_num_threads(threads);
  for (int n = 32; n <= max_n; n *= 2) {
    // The boosted puncture's box (r_c = 20) with its hole off the points, as in parfiles/boosted_puncture.yaml.
    const Level lv = test::make_level(n, 40.0 / n, true);
    std::vector<double> v[3];
    for (auto& a : v) {
      a.resize(lv.size);
      for (std::size_t i = 0; i < lv.size; ++i) a[i] = 0.01 * std::sin(0.1 * static_cast<double>(i));
    }
    const stencil::Components c{v[0].data(), v[1].data(), v[2].data()};
    const Coefficients k(lv);
    // One held point, so that the sweep runs its masked variant like the shift's (one row masked).
    std::vector<std::uint8_t> fixed(lv.size, 0);
    fixed[lv.at(n / 2, n / 2, 1)] = 1;
    // About 0.2 s of sweeps per n; the best of 5 rounds.
    const double points = static_cast<double>(lv.nx - 2) * (lv.ny - 2) * (lv.nz - 1);
    const int reps = std::max(1, static_cast<int>(2e6 / points));
    double best = 0;
    if (lower_term == "none") {
      best = best_sweep_seconds(lv, c, nullptr, NoLowerTerm{}, reps);
    } else if (lower_term == "momentum") {
      momentum::Sources s;
      s.chi = k.chi.data();
      s.weight = k.eta.data();
      s.sy = lv.sy;
      s.sz = lv.sz;
      s.inv_2h = 0.5 / lv.dx;
      best = best_sweep_seconds(lv, c, nullptr, momentum::MomentumLower<false>{s}, reps);
    } else {
      shift::Sources s;
      s.chi = k.chi.data();
      s.alpha = k.eta.data();  // any smooth positive field: the sweep's cost is what it streams
      for (int a = 0; a < 6; ++a) s.ahat[a] = k.ahat[a].data();
      s.half_mass = 0.5;
      s.x0 = lv.origin[0] - 0.1;
      s.y0 = lv.origin[1];
      s.z0 = lv.origin[2];
      s.dx = lv.dx;
      s.inv_2h = 0.5 / lv.dx;
      s.sy = lv.sy;
      s.sz = lv.sz;
      if (lower_term == "shift")
        best = best_sweep_seconds(lv, c, fixed.data(), shift::ShiftLower<true, false>{s}, reps);
      else
        best = best_sweep_seconds(lv, c, fixed.data(), shift::ShiftLower<false, false>{s}, reps);
    }
    const nlohmann::json out = {{"case", "vector_sweep"},
                                {"lower", lower_term},
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
