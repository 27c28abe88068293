#pragma once
// Orders the entries of each bin: before/after constraints first, then the order of the plugins
// list, then declaration order. A reference to an entry of an inactive plugin is dropped (so a
// plugin can order itself against optional partners); one to a missing entry of an active plugin,
// or across bins, is an error, as is a cycle.
#include <map>
#include <string>
#include <vector>

#include "bhnsid/core/plugin.hpp"

namespace bhnsid::core {

using Schedule = std::map<Bin, std::vector<const ScheduleEntry*>>;

/// `plugins` in the order of the parameter file's list.
Schedule build_schedule(const std::vector<const PluginDecl*>& plugins);

/// The schedule as printed by `bhnsid schedule` and at the start of `bhnsid run`.
std::string format_schedule(const Schedule& schedule);

}  // namespace bhnsid::core
