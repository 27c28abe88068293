#include "bhnsid/core/scheduler.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::core {

namespace {

const ScheduleEntry* find_entry(const std::vector<const PluginDecl*>& plugins, const std::string& full_name,
                                bool& plugin_active) {
  const auto dot = full_name.find('.');
  const std::string plugin = full_name.substr(0, dot);
  const std::string name = dot == std::string::npos ? std::string{} : full_name.substr(dot + 1);
  plugin_active = false;
  for (const auto* decl : plugins) {
    if (decl->name != plugin) continue;
    plugin_active = true;
    for (const auto& e : decl->schedule)
      if (e.name == name) return &e;
  }
  if (plugin_active) return nullptr;
  // "capability.entry": the entry of the active plugin that implements the capability, so that a
  // plugin orders itself against a role (hydro.outer_step) without naming the plugin that fills it.
  for (const auto* decl : plugins) {
    if (std::find(decl->implements.begin(), decl->implements.end(), plugin) == decl->implements.end()) continue;
    plugin_active = true;
    for (const auto& e : decl->schedule)
      if (e.name == name) return &e;
  }
  return nullptr;
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
        bool plugin_active = false;
        const ScheduleEntry* other = find_entry(plugins, ref, plugin_active);
        if (!plugin_active) continue;
        if (!other)
          throw InputError(fmt::format("schedule: {} is to run {} '{}', but the active plugin has no such entry",
                                       e.full_name(), direction == 0 ? "before" : "after", ref));
        if (other->bin != e.bin)
          throw InputError(fmt::format("schedule: {} ({}) is ordered against {} in another bin ({})", e.full_name(),
                                       to_string(e.bin), ref, to_string(other->bin)));
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
