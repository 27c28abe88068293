#pragma once
// A run's memory, estimated from its parameters before anything is allocated, so that a run that
// cannot fit is refused as bad input (exit 2, naming the estimate, the limit and the parameters
// that drive it) instead of dying to the OOM killer hours later. Plugins contribute through
// PluginBuilder::memory; the core sums, compares with what the machine (or its cgroup) allows,
// and `bhnsid check` prints the result.
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace bhnsid::core {

class Context;

class MemoryEstimate {
 public:
  struct Item {
    std::string plugin;
    std::string what;  ///< what is allocated and the parameters that drive it, e.g. "9 fields at grid.n = 128"
    double bytes = 0;
  };

  /// Bytes this plugin will allocate. Items with the same `key` (e.g. a grid field that several
  /// plugins register under one name) are counted once, the largest kept.
  void add(const std::string& plugin, const std::string& key, const std::string& what, double bytes);
  /// A count that a plugin estimating in the second stage turns into bytes (e.g. a solver's
  /// scratch per unknown); keys are defined by the interface headers that give them meaning.
  void count(const std::string& key, double n);
  double counted(const std::string& key) const;

  double total() const;
  const std::vector<Item>& items() const { return items_; }
  /// The largest items, "plugin: what (size)", largest first, at most `max_items`.
  std::string largest(std::size_t max_items) const;

 private:
  std::vector<Item> items_;
  std::vector<std::string> keys_;
  std::map<std::string, double> counts_;
};

/// First stage: what the plugin itself allocates; second stage: what depends on the first
/// stage's counts (it runs after every plugin's first stage).
enum class MemoryStage { own, derived };
using MemoryFn = std::function<void(const Context&, MemoryEstimate&)>;
struct MemoryEstimator {
  MemoryStage stage = MemoryStage::own;
  MemoryFn fn;
};

/// The memory this process may still use: the lesser of MemAvailable (/proc/meminfo) and the
/// cgroup's memory.max less its current use (v2, or v1's limit_in_bytes). ulimit -v is not
/// consulted: it limits virtual size, which the allocator's arenas and thread stacks inflate far
/// beyond the resident memory estimated here.
struct MemoryLimit {
  double bytes = 0;
  std::string source;  ///< where the limit comes from, for the message
};
MemoryLimit available_memory();

/// "1.5 GiB", "12.0 MiB", ...
std::string format_bytes(double bytes);

}  // namespace bhnsid::core
