#pragma once
#include <string>
#include <vector>

namespace bhnsid::core {

/// The candidate closest to `given` by edit distance, or "" when none is plausibly a misspelling.
std::string nearest_name(const std::string& given, const std::vector<std::string>& candidates);
/// " (did you mean 'x'?)" or "".
std::string did_you_mean(const std::string& given, const std::vector<std::string>& candidates);

}  // namespace bhnsid::core
