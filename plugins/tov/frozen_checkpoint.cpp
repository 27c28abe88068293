#include <fmt/format.h>

#include "bhnsid/core/errors.hpp"
#include "family.hpp"
#include "frozen_profile.hpp"

namespace bhnsid::tov {

void FrozenProfileModel::save(core::CheckpointWriter& out, const std::string& prefix) const {
  out.put(prefix + "bounds", {fold_lower_ ? 1.0 : 0.0, fold_lower_.value_or(0.0), no_solution_from_ ? 1.0 : 0.0,
                              no_solution_from_.value_or(0.0)});
  // In insertion order, which decides what is evicted next.
  out.put(prefix + "sigmas", std::vector<double>(order_.begin(), order_.end()));
  for (std::size_t k = 0; k < order_.size(); ++k) out.put(fmt::format("{}phi/{}", prefix, k), cache_.at(order_[k]).phi);
}

void FrozenProfileModel::restore(const core::CheckpointReader& in, const std::string& prefix) {
  const std::vector<double> bounds = in.reals(prefix + "bounds");
  if (bounds.size() != 4) throw core::InputError("tov: the checkpoint's frozen-profile model is malformed");
  fold_lower_ = bounds[0] != 0 ? std::optional<double>(bounds[1]) : std::nullopt;
  no_solution_from_ = bounds[2] != 0 ? std::optional<double>(bounds[3]) : std::nullopt;
  for (double s : order_) cache_.erase(s);
  order_.clear();
  const std::vector<double> sigmas = in.reals(prefix + "sigmas");
  for (std::size_t k = 0; k < sigmas.size(); ++k) {
    std::vector<double> phi = in.reals(fmt::format("{}phi/{}", prefix, k));
    if (phi.size() != r_.size()) throw core::InputError("tov: the checkpoint's frozen-profile model has another grid");
    cache_[sigmas[k]] = Entry{std::move(phi), std::nullopt};
    order_.push_back(sigmas[k]);
  }
}

void Family::save(core::CheckpointWriter& out) const {
  std::lock_guard lock(frozen_mutex_);
  std::vector<double> keys;
  for (const auto& [key, model] : frozen_) keys.insert(keys.end(), {key.first, key.second});
  out.put("frozen_keys", keys);
  std::size_t i = 0;
  for (const auto& [key, model] : frozen_) model->save(out, fmt::format("frozen/{}/", i++));
}

void Family::restore(const core::CheckpointReader& in) {
  std::lock_guard lock(frozen_mutex_);
  const std::vector<double> keys = in.reals("frozen_keys");
  if (keys.size() % 2 != 0) throw core::InputError("tov: the checkpoint's frozen-profile models are malformed");
  frozen_.clear();
  for (std::size_t i = 0; i < keys.size() / 2; ++i) {
    auto model = make_frozen(keys[2 * i], keys[2 * i + 1]);
    model->restore(in, fmt::format("frozen/{}/", i));
    frozen_.emplace(std::make_pair(keys[2 * i], keys[2 * i + 1]), std::move(model));
  }
}

}  // namespace bhnsid::tov
