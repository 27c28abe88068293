#pragma once
// Runs of parfiles/static_star.yaml through the real executable, and what the tests read back.
#include <map>
#include <functional>
#include <string>
#include <vector>

namespace bhnsid::test {

struct StarRun {
  int exit_code = -1;
  std::string output;                     ///< stdout + stderr, for INFO
  std::string status;                     ///< summary.json "status"
  std::map<std::string, double> scalars;  ///< summary.json "scalars"
  double chi_centre = 0, alpha_centre = 0;  ///< star_axis.tsv at xhat_C (the nearest axis point)
  bool has_axis = false;
};

/// Any run of a parameter file under parfiles/ with --set overrides, and the diagnostics plugin's
/// fields_axis.tsv as columns by name ("x", "chi", "beta_y", ...; empty when absent).
struct ParfileRun {
  int exit_code = -1;
  std::string output, status;
  std::map<std::string, double> scalars;
  std::map<std::string, std::vector<double>> axis;
  double scalar(const std::string& key) const;  ///< throws std::out_of_range naming the key when absent
};
ParfileRun run_parfile(const std::string& parfile, const std::vector<std::string>& sets);

/// Runs the static-star parfile with grid.n = n, grid.dx = dx and the extra --set overrides.
StarRun run_static_star(int n, double dx, const std::vector<std::string>& sets = {},
                        const std::string& parfile = "static_star.yaml");

/// The fixed-source solve (star.iterate = false: the TOV density held at sigma = R_iso)
/// at dx = 0.12, 0.06, 0.03 on r_c = 1.92, returning value(run) - reference for each; REQUIREs every
/// run to succeed.
std::vector<double> fixed_source_errors(double (*value)(const StarRun&), double reference);

/// The isolated TOV star of Gamma = 2, K = 1, rho0_c = 0.1, from the independent Python reference
/// /work/shared/physics-checks/tov.py (physics-notes §6.1 and §9 T1), which the tov plugin's tests
/// also reproduce to 1e-9: the values every static-star test compares with.
namespace tov01 {
inline constexpr double adm_mass = 0.126957417269;
inline constexpr double rest_mass = 0.135312727055;
inline constexpr double radius_areal = 1.00473500683;
inline constexpr double radius_isotropic = 0.873162703434;
inline constexpr double lapse_center = 0.72037884898;
inline constexpr double psi_center = 1.15989819199;
/// C_B = h_max alpha_c = sqrt(1 - 2M/R) (physics-notes §9 T1): 0.864455.
double bernoulli_constant();
}  // namespace tov01

}  // namespace bhnsid::test
