#pragma once
// Schedule bins and entries. PARAMCHECK runs first, before the run directory exists and also in
// `bhnsid check`, so its entries may only read parameters; STARTUP..INITIAL then run once, SOLVE/UPDATE/CHECK form the loop, then
// ANALYSIS, OUTPUT and TERMINATE run once, also after a failed loop so the last state is kept.
// RETREAT runs only when a SOLVE entry fails with a StepFailure: each entry undoes what its plugin
// changed since that SOLVE began or in the UPDATE before it, and UPDATE then runs again with a
// smaller step.
#include <functional>
#include <string>
#include <vector>

namespace bhnsid::core {

class Context;

enum class Bin { paramcheck, startup, setup, initial, solve, update, check, retreat, analysis, output, terminate };

const char* to_string(Bin bin);
bool in_loop(Bin bin);
/// All bins in execution order.
const std::vector<Bin>& all_bins();

/// What a CHECK entry reports after each loop iteration.
struct Convergence {
  bool converged = false;
  std::string detail;  ///< e.g. "max |d sigma| = 3e-5 (tol 1e-4)", printed with the iteration
};

using ScheduledFn = std::function<void(Context&)>;
using CheckFn = std::function<Convergence(Context&)>;

/// An ordering constraint: "capability.entry" names the entry `entry` of whichever active plugin
/// implements `capability` (split at the last dot: capabilities may hold dots, entry names may not),
/// so that a plugin orders itself against a role and never against the plugin that fills it.
struct ScheduleRef {
  std::string target;
  /// false: no active plugin implementing the capability is an error naming the reference;
  /// true: the constraint holds only when one is active (a hole without a star, a star without a hole).
  bool if_present = false;
};

struct ScheduleEntry {
  std::string plugin;  ///< filled in by the core
  std::string name;    ///< an identifier, unique within the plugin; referred to as "capability.name"
  Bin bin = Bin::startup;
  std::string doc;
  std::vector<ScheduleRef> before;  ///< entries of the same bin this must precede
  std::vector<ScheduleRef> after;   ///< entries of the same bin this must follow
  ScheduledFn fn;                   ///< every bin but CHECK
  CheckFn check;                    ///< CHECK only

  std::string full_name() const { return plugin + "." + name; }
};

}  // namespace bhnsid::core
