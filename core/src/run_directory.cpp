#include "bhnsid/core/run_directory.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bhnsid/core/atomic_file.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/owned_entry.hpp"
#include "checkpoint_file.hpp"

namespace bhnsid::core {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr const char* marker_format = "bhnsid run directory";
constexpr int marker_version = 1;

struct Marker {
  bool present = false;
  std::string kind;
  long pid = 0;
  std::vector<std::string> files;
  std::vector<std::string> folders;  ///< sub-directories whose every entry the program wrote
};

bool listed(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Reads the marker; a file of that name in another format is reported, never taken for ours.
Marker read_marker(const fs::path& dir) {
  Marker m;
  const fs::path path = dir / run_marker_name;
  if (!require_own_entry(path, EntryKind::regular_file)) return m;
  std::string text;
  {
    // A marker lists file names: a megabyte is thousands of runs' worth; more is not ours.
    constexpr std::size_t max_bytes = 1 << 20;
    const int fd = open_own_file_for_reading(path, "the run directory's marker");
    char buffer[65536];
    ssize_t n = 0;
    while ((n = ::read(fd, buffer, sizeof buffer)) > 0 && text.size() <= max_bytes) text.append(buffer, static_cast<std::size_t>(n));
    ::close(fd);
    if (text.size() > max_bytes) text.clear();
  }
  try {
    const json j = json::parse(text);
    if (j.at("format") != marker_format || j.at("version") != marker_version) throw std::runtime_error("format");
    m.kind = j.at("kind").get<std::string>();
    m.pid = j.at("pid").get<long>();
    const auto names = [](const json& list, std::vector<std::string>& out) {
      for (const auto& f : list) {
        const std::string name = f.get<std::string>();
        if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
          throw std::runtime_error("name");
        out.push_back(name);
      }
    };
    names(j.at("files"), m.files);
    if (j.contains("folders")) names(j.at("folders"), m.folders);
  } catch (const std::exception&) {
    throw InputError(fmt::format("{}: {} is not a marker this program wrote (unreadable or another format); not "
                                 "replacing the directory",
                                 dir.string(), run_marker_name));
  }
  m.present = true;
  return m;
}

// A temporary file of write_file_atomic ("NAME.tmp.XXXXXX") left by a killed run of ours: by its name
// beside a recorded NAME, and a regular file of one name (a folder or a link so named is the user's).
bool is_our_temporary_name(const std::string& entry, const std::vector<std::string>& files) {
  for (const std::string& f : files)
    if (entry.size() == f.size() + 11 && entry.compare(0, f.size() + 5, f + ".tmp.") == 0) return true;
  return entry.size() == std::strlen(run_marker_name) + 11 && entry.rfind(std::string(run_marker_name) + ".tmp.", 0) == 0;
}

bool is_our_temporary(const fs::path& dir, const std::string& entry, const std::vector<std::string>& files) {
  struct stat st {};
  return is_our_temporary_name(entry, files) && ::lstat((dir / entry).c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
         st.st_nlink == 1;
}

// Entry names of a directory, without the exceptions of a range-for over directory_iterator.
std::vector<std::string> entries_of(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
    names.push_back(it->path().filename().string());
  if (ec) throw InputError(fmt::format("{}: cannot list the directory: {}", dir.string(), ec.message()));
  return names;
}

// What a --force takeover found below a previous run's directory: entries the program did not
// write, and locks on recorded sub-directories that are run directories themselves (a validate
// series' level runs), held until their removal so that a run still alive there is refused.
struct OldContents {
  std::vector<std::string> foreign;
  std::vector<int> locks;
  ~OldContents() {
    for (int fd : locks) ::close(fd);
  }
};

// A recorded folder (the checkpoints) is the program's only in the entries it names itself: a note
// the user put there, or a symbolic link where the folder was, is foreign.
void inspect_folder(const fs::path& dir, const std::string& prefix, OldContents& out) {
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0) return;
  if (!S_ISDIR(st.st_mode)) {
    out.foreign.push_back(prefix + " (not the folder bhnsid made: a symbolic link or a file)");
    return;
  }
  for (const std::string& name : entries_of(dir)) {
    struct stat entry {};
    if (!is_checkpoint_entry_name(name) || ::lstat((dir / name).c_str(), &entry) != 0 || !S_ISREG(entry.st_mode))
      out.foreign.push_back(prefix + "/" + name);
  }
}

void inspect(const fs::path& dir, const Marker& marker, const std::string& prefix, OldContents& out) {
  for (const std::string& name : entries_of(dir)) {
    if (name == run_marker_name || is_our_temporary(dir, name, marker.files)) continue;
    if (listed(marker.folders, name)) {
      inspect_folder(dir / name, prefix + name, out);
      continue;
    }
    if (!listed(marker.files, name)) {
      out.foreign.push_back(prefix + name);
      continue;
    }
    const fs::path path = dir / name;
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) continue;
    const Marker inner = read_marker(path);
    if (!inner.present) {
      out.foreign.push_back(prefix + name + "/ (no marker)");
      continue;
    }
    const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0 || ::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      if (fd >= 0) ::close(fd);
      throw InputError(fmt::format("{}: in use by another bhnsid process (PID {}); --force never touches a directory "
                                   "in use",
                                   path.string(), inner.pid));
    }
    out.locks.push_back(fd);
    inspect(path, inner, prefix + name + "/", out);
  }
}

// Removes what the previous run recorded (and its temporaries), each failure reported.
void remove_old_run(const fs::path& dir, const Marker& marker) {
  for (const std::string& name : entries_of(dir)) {
    if (name == run_marker_name) continue;
    const bool temporary = is_our_temporary(dir, name, marker.files);
    if (!listed(marker.files, name) && !listed(marker.folders, name) && !temporary)
      continue;  // cannot happen after inspect(); never remove what is not listed
    std::error_code ec;
    if (temporary && !listed(marker.files, name)) {
      fs::remove(dir / name, ec);
      if (ec) throw InputError(fmt::format("{}: cannot remove the old run's {}: {}", dir.string(), name, ec.message()));
      continue;
    }
    if (listed(marker.folders, name) && !listed(marker.files, name)) {
      // inspect() found nothing but our own entries there: those go, then the folder if empty.
      for (const std::string& entry : entries_of(dir / name))
        if (is_checkpoint_entry_name(entry)) fs::remove(dir / name / entry, ec);
      if (!ec) fs::remove(dir / name, ec);
    } else {
      fs::remove_all(dir / name, ec);
    }
    if (ec) throw InputError(fmt::format("{}: cannot remove the old run's {}: {}", dir.string(), name, ec.message()));
  }
}

bool is_same_or_inside(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin(), o = outer.begin();
  for (; o != outer.end(); ++i, ++o)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace

RunDirectory::RunDirectory(fs::path dir, bool force, std::string kind, const std::vector<fs::path>& protect)
    : dir_(std::move(dir)), kind_(std::move(kind)), started_(now_utc()) {
  if (dir_.empty()) throw InputError("the run directory name is empty; expected a directory, e.g. --output runs/case");
  // "runs/new/" names runs/new: without this its parent_path() would be the directory itself.
  dir_ = dir_.lexically_normal();
  if (!dir_.has_filename() && dir_.has_parent_path()) dir_ = dir_.parent_path();
  std::error_code ec;
  if (dir_.has_parent_path()) {
    // The first missing folder above: what abandon() may remove again, when empty.
    for (fs::path p = dir_.parent_path(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
      first_created_parent_ = p;
      if (!p.has_parent_path() || p.parent_path() == p) break;
    }
    fs::create_directories(dir_.parent_path(), ec);
    if (ec)
      throw InputError(fmt::format("{}: cannot create the run directory (the folders above it): {}", dir_.string(), ec.message()));
  }
  if (::mkdir(dir_.c_str(), 0755) == 0) {
    created_ = true;
  } else if (errno != EEXIST) {
    const int error = errno;
    remove_created_parents();
    throw InputError(fmt::format("{}: cannot create the run directory: {}", dir_.string(), std::strerror(error)));
  } else if (!force) {
    throw InputError(fmt::format("{}: the run directory exists; choose another with --output DIR or replace it with "
                                 "--force",
                                 dir_.string()));
  } else {
    struct stat st {};
    if (::lstat(dir_.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
      throw InputError(fmt::format("{}: exists and is not a directory (or is a symbolic link); --force only replaces "
                                   "run directories",
                                   dir_.string()));
    const fs::path target = fs::canonical(dir_, ec);
    if (ec) throw InputError(fmt::format("{}: cannot resolve the directory: {}", dir_.string(), ec.message()));
    const fs::path cwd = fs::current_path(ec);
    if (ec || is_same_or_inside(cwd, target))
      throw InputError(fmt::format("{}: is the working directory or a folder above it; --force never replaces it",
                                   dir_.string()));
    for (const fs::path& p : protect) {
      const fs::path keep = fs::weakly_canonical(p, ec);
      if (!keep.empty() && is_same_or_inside(keep, target))
        throw InputError(fmt::format("{}: holds the parameter file ({}); --force never replaces it", dir_.string(),
                                     p.string()));
    }
  }
  lock();
  try {
    if (!created_) {
      const Marker old = read_marker(dir_);
      OldContents found;
      if (old.present)
        inspect(dir_, old, "", found);
      else
        found.foreign = entries_of(dir_);
      if (!found.foreign.empty()) {
        std::sort(found.foreign.begin(), found.foreign.end());
        const std::size_t shown = std::min<std::size_t>(found.foreign.size(), 5);
        throw InputError(fmt::format(
            "{}: {}; --force only replaces what bhnsid wrote, and this directory also holds {} (of {} such entries); "
            "move them away or choose another --output",
            dir_.string(),
            old.present ? "is a bhnsid " + old.kind + " directory"
                        : "is not a bhnsid run directory (no " + std::string(run_marker_name) + ")",
            fmt::join(found.foreign.begin(), found.foreign.begin() + static_cast<std::ptrdiff_t>(shown), ", "),
            found.foreign.size()));
      }
      if (old.present) remove_old_run(dir_, old);
    }
    write_marker();
  } catch (...) {
    if (created_) abandon();
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

void RunDirectory::lock() {
  fd_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC | O_NOFOLLOW);
  if (fd_ < 0) {
    const int error = errno;
    if (created_) {
      ::rmdir(dir_.c_str());
      remove_created_parents();
    }
    throw InputError(fmt::format("{}: cannot open the run directory: {}", dir_.string(), std::strerror(error)));
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK) {
      // A file system without flock (Lustre mounted without -o flock answers ENOSYS): the run goes
      // on, but nothing then keeps a second run out of this directory; said once.
      std::fprintf(stderr, "bhnsid: warning: %s: cannot lock the run directory (%s); two runs into it at once are not "
                   "excluded on this file system\n", dir_.c_str(), std::strerror(errno));
      return;
    }
    ::close(fd_);
    fd_ = -1;
    long pid = 0;
    try {
      pid = read_marker(dir_).pid;
    } catch (const InputError&) {
    }
    throw InputError(fmt::format("{}: in use by another bhnsid process{}; wait for it to finish or choose another "
                                 "--output",
                                 dir_.string(), pid > 0 ? fmt::format(" (PID {})", pid) : std::string()));
  }
}

RunDirectory::RunDirectory(fs::path dir, std::string kind, ReopenTag)
    : dir_(std::move(dir)), kind_(std::move(kind)), started_(now_utc()), reopened_(true) {
  if (dir_.empty()) throw InputError("the run directory name is empty; expected the directory of the run to resume");
  dir_ = dir_.lexically_normal();
  if (!dir_.has_filename() && dir_.has_parent_path()) dir_ = dir_.parent_path();
  struct stat st {};
  if (::lstat(dir_.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw InputError(fmt::format("{}: there is no run directory to resume (run without --resume to start the run)",
                                 dir_.string()));
  lock();
  try {
    const Marker old = read_marker(dir_);
    if (!old.present)
      throw InputError(fmt::format("{}: is not a bhnsid run directory (no {}); --resume only continues a run this "
                                   "program wrote",
                                   dir_.string(), run_marker_name));
    if (old.kind != kind_)
      throw InputError(fmt::format("{}: is a bhnsid {} directory, not a {} directory", dir_.string(), old.kind, kind_));
    // Everything the earlier run wrote is checked now, before the resume computes anything: a link or
    // FIFO left at summary.json would otherwise be found only when the run ends.
    for (const std::string& f : old.files) require_own_entry(dir_ / f, EntryKind::regular_file);
    for (const std::string& f : old.folders) require_own_entry(dir_ / f, EntryKind::folder);
    files_ = old.files;
    folders_ = old.folders;
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

RunDirectory::~RunDirectory() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

void RunDirectory::record(const std::string& name) {
  if (std::find(files_.begin(), files_.end(), name) != files_.end()) return;
  files_.push_back(name);
  write_marker();
}

void RunDirectory::take_over() { write_marker(); }

void RunDirectory::record_folder(const std::string& name) {
  if (listed(folders_, name)) return;
  folders_.push_back(name);
  write_marker();
}

void RunDirectory::write_marker() {
  json j;
  j["format"] = marker_format;
  j["version"] = marker_version;
  j["kind"] = kind_;
  j["pid"] = static_cast<long>(::getpid());
  j["started"] = started_;
  j["files"] = files_;
  if (!folders_.empty()) j["folders"] = folders_;
  write_file_atomic(dir_ / run_marker_name, j.dump(1, ' ', false, json::error_handler_t::replace) + "\n");
}

void RunDirectory::abandon() {
  if (reopened_) return;  // what a resumed run found there is the earlier run's: never removed
  std::error_code ec;
  for (const std::string& f : files_) fs::remove_all(dir_ / f, ec);
  for (const std::string& f : folders_) fs::remove_all(dir_ / f, ec);
  files_.clear();
  folders_.clear();
  fs::remove(dir_ / run_marker_name, ec);
  if (!created_) return;
  fs::remove(dir_, ec);  // only if empty: never more than we made
  remove_created_parents();
}

void RunDirectory::remove_created_parents() {
  if (first_created_parent_.empty()) return;
  std::error_code ec;
  for (fs::path p = dir_.parent_path(); !p.empty(); p = p.parent_path()) {
    if (!fs::remove(p, ec)) break;  // not empty: something else lives there now
    if (p == first_created_parent_) break;
  }
}

}  // namespace bhnsid::core
