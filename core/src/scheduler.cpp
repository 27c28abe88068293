#include "bhnsid/core/scheduler.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::core {

namespace {

// The entry a reference names, or nullptr for an absent optional capability; every other failure
// to resolve is an InputError that names the entry, the reference and what is missing.
const ScheduleEntry* resolve(const std::vector<const PluginDecl*>& plugins, const ScheduleEntry& from,
                             const ScheduleRef& ref, const char* direction) {
  const std::size_t dot = ref.target.rfind('.');
  const std::string capability = ref.target.substr(0, dot == std::string::npos ? 0 : dot);
  const std::string entry = dot == std::string::npos ? std::string{} : ref.target.substr(dot + 1);
  const auto says = [&](const std::string& why) {
    return InputError(fmt::format("schedule: {} is to run {} '{}', but {}", from.full_name(), direction, ref.target, why));
  };
  if (capability.empty() || entry.empty()) throw says("a reference is 'capability.entry'");
  for (const auto* decl : plugins) {
    if (std::find(decl->implements.begin(), decl->implements.end(), capability) == decl->implements.end()) continue;
    for (const auto& e : decl->schedule)
      if (e.name == entry) return &e;
    throw says(fmt::format("{}, which implements '{}', has no entry '{}'", decl->name, capability, entry));
  }
  if (ref.if_present) return nullptr;
  for (const auto* decl : plugins)
    if (decl->name == capability)
      throw says(fmt::format("references name a capability, and the plugin '{}' implements {}", capability,
                             decl->implements.empty() ? std::string("none") : fmt::format("'{}'", fmt::join(decl->implements, "', '"))));
  throw says(fmt::format("no active plugin implements '{}' (add one that does to plugins:)", capability));
}

// Kahn's algorithm; among the ready entries the earliest in (plugin order, declaration order) goes first.
std::vector<const ScheduleEntry*> order_bin(const std::vector<const ScheduleEntry*>& entries,
                                            const std::vector<const PluginDecl*>& plugins) {
  const std::size_t n = entries.size();
  std::vector<std::set<std::size_t>> successors(n);
  std::vector<std::size_t> in_degree(n, 0);
  const auto index_of = [&](const ScheduleEntry* e) {
    return static_cast<std::size_t>(std::find(entries.begin(), entries.end(), e) - entries.begin());
  };
  const auto add_edge = [&](std::size_t from, std::size_t to) {
    if (successors[from].insert(to).second) ++in_degree[to];
  };
  for (std::size_t i = 0; i < n; ++i) {
    const ScheduleEntry& e = *entries[i];
    for (int direction = 0; direction < 2; ++direction) {
      for (const auto& ref : direction == 0 ? e.before : e.after) {
        const ScheduleEntry* other = resolve(plugins, e, ref, direction == 0 ? "before" : "after");
        if (!other) continue;
        if (other->bin != e.bin)
          throw InputError(fmt::format("schedule: {} ({}) is ordered against {} ({}) in another bin ({})", e.full_name(),
                                       to_string(e.bin), ref.target, other->full_name(), to_string(other->bin)));
        const std::size_t j = index_of(other);
        if (j == i) throw InputError(fmt::format("schedule: {} is ordered against itself", e.full_name()));
        direction == 0 ? add_edge(i, j) : add_edge(j, i);
      }
    }
  }
  std::vector<const ScheduleEntry*> ordered;
  std::vector<bool> done(n, false);
  for (std::size_t step = 0; step < n; ++step) {
    std::size_t pick = n;
    for (std::size_t i = 0; i < n && pick == n; ++i)
      if (!done[i] && in_degree[i] == 0) pick = i;
    if (pick == n) {
      std::vector<std::string> stuck;
      for (std::size_t i = 0; i < n; ++i)
        if (!done[i]) stuck.push_back(entries[i]->full_name());
      throw InputError(fmt::format("schedule: the before/after constraints of {} form a cycle: {}",
                                   to_string(entries.front()->bin), fmt::join(stuck, ", ")));
    }
    done[pick] = true;
    ordered.push_back(entries[pick]);
    for (std::size_t j : successors[pick]) --in_degree[j];
  }
  return ordered;
}

}  // namespace

Schedule build_schedule(const std::vector<const PluginDecl*>& plugins) {
  Schedule schedule;
  for (Bin bin : all_bins()) {
    std::vector<const ScheduleEntry*> entries;
    for (const auto* decl : plugins)
      for (const auto& e : decl->schedule)
        if (e.bin == bin) entries.push_back(&e);
    if (!entries.empty()) schedule[bin] = order_bin(entries, plugins);
  }
  return schedule;
}

std::string format_schedule(const Schedule& schedule) {
  std::string out;
  bool loop_open = false;
  for (Bin bin : all_bins()) {
    auto it = schedule.find(bin);
    if (in_loop(bin) && !loop_open && (schedule.count(Bin::solve) || schedule.count(Bin::update) || schedule.count(Bin::check))) {
      out += "loop (until every CHECK reports converged, at most run.max_iterations):\n";
      loop_open = true;
    }
    if (it == schedule.end()) continue;
    const char* indent = in_loop(bin) ? "  " : "";
    out += fmt::format("{}{}{}\n", indent, to_string(bin),
                       bin == Bin::retreat ? " (only after a SOLVE step failure; then UPDATE and SOLVE again)" : "");
    for (const auto* e : it->second)
      out += fmt::format("{}  {:<36} {}\n", indent, e->full_name(), e->doc);
  }
  if (out.empty()) out = "(nothing scheduled)\n";
  return out;
}

}  // namespace bhnsid::core
