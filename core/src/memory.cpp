#include "bhnsid/core/memory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace bhnsid::core {

void MemoryEstimate::add(const std::string& plugin, const std::string& key, const std::string& what, double bytes) {
  const auto it = std::find(keys_.begin(), keys_.end(), key);
  if (it != keys_.end()) {
    Item& old = items_[static_cast<std::size_t>(it - keys_.begin())];
    if (bytes > old.bytes) old = Item{plugin, what, bytes};
    return;
  }
  keys_.push_back(key);
  items_.push_back(Item{plugin, what, bytes});
}

void MemoryEstimate::count(const std::string& key, double n) { counts_[key] += n; }

double MemoryEstimate::counted(const std::string& key) const {
  const auto it = counts_.find(key);
  return it == counts_.end() ? 0 : it->second;
}

double MemoryEstimate::total() const {
  double sum = 0;
  for (const Item& item : items_) sum += item.bytes;
  return sum;
}

std::string MemoryEstimate::largest(std::size_t max_items) const {
  std::vector<const Item*> sorted;
  for (const Item& item : items_) sorted.push_back(&item);
  std::stable_sort(sorted.begin(), sorted.end(), [](const Item* a, const Item* b) { return a->bytes > b->bytes; });
  std::string out;
  for (std::size_t i = 0; i < sorted.size() && i < max_items; ++i)
    out += fmt::format("{}{}: {} ({})", i ? "; " : "", sorted[i]->plugin, sorted[i]->what, format_bytes(sorted[i]->bytes));
  return out;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (std::fabs(bytes) >= 1024 && u < 6) {
    bytes /= 1024;
    ++u;
  }
  return u == 0 ? fmt::format("{:.0f} B", bytes) : fmt::format("{:.1f} {}", bytes, units[u]);
}

namespace {

// One number from a file such as memory.max; "max" or anything unreadable gives infinity.
double read_number(const std::string& path) {
  std::ifstream in(path);
  std::string word;
  if (!(in >> word) || word == "max") return std::numeric_limits<double>::infinity();
  try {
    std::size_t used = 0;
    const double v = std::stod(word, &used);
    return used == word.size() && v >= 0 ? v : std::numeric_limits<double>::infinity();
  } catch (const std::exception&) {
    return std::numeric_limits<double>::infinity();
  }
}

// The cgroup (v2 unified, else v1 memory controller) this process belongs to, from /proc/self/cgroup.
// Inside a container the hierarchy may be mounted at the group itself, so the group's path is
// tried below the mount point and then the mount point alone.
void cgroup_limit(MemoryLimit& limit) {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const std::string path = line.substr(second + 1);
    const bool v2 = controllers.empty();
    if (!v2 && ("," + controllers + ",").find(",memory,") == std::string::npos) continue;
    const std::vector<std::string> mounts =
        v2 ? std::vector<std::string>{"/sys/fs/cgroup", "/sys/fs/cgroup/unified"} : std::vector<std::string>{"/sys/fs/cgroup/memory"};
    const std::string max_file = v2 ? "/memory.max" : "/memory.limit_in_bytes";
    const std::string current_file = v2 ? "/memory.current" : "/memory.usage_in_bytes";
    for (const std::string& mount : mounts)
      for (const std::string& dir : {mount + path, mount}) {
        if (!std::ifstream(dir + max_file)) continue;
        const double max = read_number(dir + max_file);
        // v1 reports "no limit" as a huge page-rounded number.
        if (!std::isfinite(max) || max >= 0x1p62) continue;
        const double current = read_number(dir + current_file);
        const double left = std::max(0.0, max - (std::isfinite(current) ? current : 0.0));
        if (left < limit.bytes)
          limit = MemoryLimit{left, fmt::format("the cgroup limit {} less its current use", dir + max_file)};
      }
  }
}

}  // namespace

MemoryLimit available_memory() {
  MemoryLimit limit{std::numeric_limits<double>::infinity(), "no limit found"};
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream row(line);
    std::string key;
    double kib = 0;
    if (row >> key >> kib && key == "MemAvailable:") limit = MemoryLimit{kib * 1024, "MemAvailable in /proc/meminfo"};
  }
  cgroup_limit(limit);
  return limit;
}

}  // namespace bhnsid::core
