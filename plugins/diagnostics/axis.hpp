#pragma once
// The solution along the x axis and its largest deviations from flat space, for tests and plots.
#include <map>
#include <string>

#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/lapse.hpp"

namespace bhnsid::diagnostics {

/// fields_axis.tsv: x, then every shared field that exists (chi, the lapse's regular part under its
/// field name and alpha, each component of wvec and beta, rho0) on the x axis of the finest level.
std::string axis_table(Grid& grid, const Lapse* lapse);

/// max |chi - 1|, max |R - 1| of the lapse's regular part R, max |W^i|, max |beta^i| over the finest
/// level, for the fields that exist: "chi_deviation_max", "<R's field name>_deviation_max" (eta for
/// the paper's lapse), "wvec_max", "shift_max".
std::map<std::string, double> deviations(const Grid& grid, const Lapse* lapse);

}  // namespace bhnsid::diagnostics
