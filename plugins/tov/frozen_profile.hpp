#pragma once
// Model C of physics-notes section 4.5 (the "frozen-profile TOV" sigma model) for one TOV star and
// one hatted surface radius: the spherical hatted field equations with source sigma^2 x the star's
// fixed profile, continued in sigma from sigma_tov (README.md gives the discretization).
#include <array>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bhnsid/core/checkpoint.hpp"
#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/tov_family.hpp"

namespace bhnsid::tov {

struct FrozenSettings {
  /// Grid intervals on [0, rhat_star]. The scheme is fourth order: 400 puts the discretization
  /// error of alpha and phi near 1e-11 for the Gamma = 2 star of rho_c = 0.1.
  int points = 400;
  /// Largest continuation step in sigma, relative to sigma (physics-notes: 0.5 %).
  double step = 0.005;
};

class FrozenProfileModel {
 public:
  /// `star` is the TOV star of the central density rho_max (its profile becomes the frozen source).
  FrozenProfileModel(const Eos& eos, const TovStar& star, double rhat_star, FrozenSettings settings);

  /// The solution at sigma, continued from the nearest solution already known (the first from the
  /// TOV star at sigma_tov). Not thread safe: the caller serializes. Throws core::RunFailure above
  /// the fold or when the continuation fails.
  FrozenProfileSolution solve(double sigma);

  /// The continuation's known solutions (the next solve starts from the nearest, so they shape
  /// its last bits) and the fold bounds, under entry names starting with `prefix`
  /// (frozen_checkpoint.cpp).
  void save(core::CheckpointWriter& out, const std::string& prefix) const;
  void restore(const core::CheckpointReader& in, const std::string& prefix);

  double sigma_tov() const { return sigma_tov_; }
  /// The largest sigma at which a solution is known, when a continuation upwards has hit the fold.
  std::optional<double> fold_lower_bound() const { return fold_lower_; }
  /// Newton iterations spent by the last solve() (all continuation steps), for the tests.
  int last_newton_iterations() const { return last_iterations_; }

 private:
  // Band matrix of the discrete equations: rows 0..N, sub/main/super diagonal, and the one entry
  // (N, N-2) of the outer boundary row.
  struct Band {
    std::vector<double> lo, di, up;
    double extra = 0;
  };
  using Weights = std::vector<std::array<double, 3>>;

  struct QPoint {
    double s, w, e, e2s;  // quadrature node, weight, E and E + 2S there
  };
  struct Profile {
    std::vector<double> r_iso, enthalpy, psi;
  };
  void compute_weights(const Eos& eos, const Profile& prof, double radius_iso);
  void assemble(double c, const Weights& w, const std::vector<double>& dq, Band& band) const;
  // Solves band x = rhs in place (rhs becomes x); returns the sign of the determinant (0: singular).
  static int solve_band(Band band, std::vector<double>& rhs);
  bool newton(double sigma, std::vector<double>& phi, int& det_sign);
  FrozenProfileSolution finish(double sigma, const std::vector<double>& phi) const;
  void remember(double sigma, std::vector<double> phi, std::optional<FrozenProfileSolution> full);
  std::string describe() const;

  FrozenSettings settings_;
  double rho_max_, rhat_star_, sigma_tov_;
  int n_;                      // grid intervals; nodes r_i = i h, i = 0..n_
  double h_;
  std::vector<double> r_;
  Weights w_e_, w_s_;          // product-integration weights of E and of E + 2S, per row
  int det_sign_ = 0;           // sign of the Newton Jacobian on the TOV branch
  std::optional<double> fold_lower_, no_solution_from_;
  struct Entry {
    std::vector<double> phi;
    std::optional<FrozenProfileSolution> full;
  };
  std::map<double, Entry> cache_;
  std::deque<double> order_;  // insertion order of the evictable cache entries
  int last_iterations_ = 0;
};

}  // namespace bhnsid::tov
