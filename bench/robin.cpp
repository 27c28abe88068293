#include "robin.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "multigrid/boundary_rows.hpp"
#include "test_level.hpp"
#include "timing.hpp"

namespace bhnsid::bench {

int robin_rows(int n, int threads) {
  if (n < 8 || (n & (n - 1)) != 0) {
    std::cerr << "bhnsid-bench robin: --n must be a power of 2 (intervals), got " << n << "\n";
    return 2;
  }
  omp_set_num_threads(threads);
  const Level lv = test::make_level(n, 40.0 / n, true);
  const multigrid::RobinRows puncture_rows = multigrid::robin_stencils(lv, {0.1, 0.0, 0.0}, false);
  const multigrid::RobinRows origin_rows = multigrid::robin_stencils(lv, {0.0, 0.0, 0.0}, false);
  // Smooth stand-ins: chi and eta near 1, the vector components near 0.
  std::vector<std::vector<double>> fields(8, std::vector<double>(lv.size));
  for (std::size_t a = 0; a < fields.size(); ++a)
    for (std::size_t i = 0; i < lv.size; ++i)
      fields[a][i] = (a < 2 ? 1.0 : 0.0) + 0.01 * std::sin(0.1 * static_cast<double>(i) + static_cast<double>(a));
  std::vector<multigrid::RobinTarget> scalars, vectors;
  std::vector<multigrid::RobinResidual> scalar_res, vector_res;
  for (std::size_t a = 0; a < fields.size(); ++a) {
    const double u_inf = a < 2 ? 1.0 : 0.0;
    (a < 2 ? scalars : vectors).push_back({fields[a].data(), u_inf, nullptr, nullptr});
    (a < 2 ? scalar_res : vector_res).push_back({fields[a].data(), u_inf, nullptr, nullptr, nullptr});
  }
  std::vector<double> out(std::max(puncture_rows.size(), origin_rows.size()) * 6);
  const int reps = std::max(1, static_cast<int>(2e7 / static_cast<double>(puncture_rows.index.size() * 8)));
  const double relax_scalars = best_seconds(reps, [&] { multigrid::robin_relax(puncture_rows, scalars); });
  const double relax_vectors = best_seconds(reps, [&] { multigrid::robin_relax(origin_rows, vectors); });
  const double residual_scalars =
      best_seconds(reps, [&] { multigrid::robin_residual_rows(puncture_rows, scalar_res, out.data()); });
  const double residual_vectors =
      best_seconds(reps, [&] { multigrid::robin_residual_rows(origin_rows, vector_res, out.data()); });
  const nlohmann::json json = {{"case", "robin_rows"},
                               {"n", n},
                               {"threads", threads},
                               {"rows", puncture_rows.size()},
                               {"entries_puncture_centre", puncture_rows.index.size()},
                               {"entries_origin_centre", origin_rows.index.size()},
                               {"relax_chi_eta_ms", relax_scalars * 1e3},
                               {"relax_w_beta_ms", relax_vectors * 1e3},
                               {"residual_chi_eta_ms", residual_scalars * 1e3},
                               {"residual_w_beta_ms", residual_vectors * 1e3}};
  std::cout << json.dump() << std::endl;
  return 0;
}

}  // namespace bhnsid::bench
