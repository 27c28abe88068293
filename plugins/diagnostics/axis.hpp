#pragma once
// The solution along the x axis and its largest deviations from flat space, for tests and plots.
#include <map>
#include <string>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::diagnostics {

/// fields_axis.tsv: x, then every shared field that exists (chi, eta, each component of wvec and
/// beta, rho0) on the x axis of the finest level.
std::string axis_table(const Grid& grid);

/// max |chi - 1|, max |eta - 1|, max |W^i|, max |beta^i| over the finest level, for the fields that
/// exist: "chi_deviation_max", "eta_deviation_max", "wvec_max", "shift_max".
std::map<std::string, double> deviations(const Grid& grid);

}  // namespace bhnsid::diagnostics
