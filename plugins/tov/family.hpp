#pragma once
// The tov plugin's TovFamily: the stars of one EOS, the maximum-mass stars (found once, cached) and
// the stable-branch star of a given rest mass, and the frozen-profile sigma models (physics-notes 4.5).
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>

#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/tov_family.hpp"
#include "frozen_profile.hpp"
#include "solver.hpp"

namespace bhnsid::tov {

struct SearchSettings {
  /// The maxima are searched for on a logarithmic scan of `scan_points` central densities in
  /// [density_min, density_max], then refined by golden-section search to `relative_tolerance` in rho_c.
  double density_min = 1e-3, density_max = 3.0;
  int scan_points = 40;
  double relative_tolerance = 1e-9;
};

class Family final : public TovFamily {
 public:
  Family(const Eos& eos, Settings settings, SearchSettings search = {}, FrozenSettings frozen = {});

  TovStar star(double central_density) const override;
  double adm_mass_from_rest_mass(double rest_mass) const override;
  TovStar star_from_rest_mass(double rest_mass) const override;
  TovStar maximum_mass_star() const override;
  TovStar maximum_rest_mass_star() const override;
  FrozenProfileSolution frozen_profile(double rho_max, double rhat_star, double sigma) const override;

  /// The frozen-profile models a run has used, with their continuation caches.
  void save(core::CheckpointWriter& out) const;
  void restore(const core::CheckpointReader& in);

  /// The stable-branch central density of the star of rest mass M0.
  double central_density_from_rest_mass(double rest_mass) const;

 private:
  double maximize(bool rest_mass) const;  // the central density of the maximum
  std::unique_ptr<FrozenProfileModel> make_frozen(double rho_max, double rhat_star) const;

  const Eos& eos_;
  Settings settings_;
  SearchSettings search_;
  mutable std::mutex mutex_;
  mutable std::optional<TovStar> max_adm_, max_rest_;
  // One model per (rho_max, rhat_star), each with its own grid and continuation cache; the hydro
  // iteration uses one pair for a whole run, so a handful is plenty.
  FrozenSettings frozen_settings_;
  mutable std::mutex frozen_mutex_;
  mutable std::map<std::pair<double, double>, std::unique_ptr<FrozenProfileModel>> frozen_;
};

}  // namespace bhnsid::tov
