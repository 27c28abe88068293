// bhnsid plot RUN_DIR: runs the plot script that each plugin of the run ships beside its library
// (NAME.plot.py, bhnsid_add_plugin(... PLOT script.py)) as `python3 SCRIPT RUN_DIR STAGING`. The
// core knows neither the fields nor the pictures: a plugin that owns the physics draws it.
//
// A script writes by name, and a name in the output folder may be a symbolic link or a picture the
// user keeps there. So each script writes into STAGING, a fresh private folder (mkdtemp) inside the
// output folder, and the core moves the pictures into place by rename, which never follows a link.
// A name already taken is replaced only when it is a regular file listed in the folder's record
// `.bhnsid-plots` (what plot wrote there before); anything else is refused, naming it, and nothing
// is moved. The scripts run by execv with an argv: no shell ever sees a path.
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/interrupt.hpp"
#include "bhnsid/core/owned_entry.hpp"
#include "bhnsid/core/parfile.hpp"
#include "bhnsid/core/plugin_loader.hpp"
#include "commands.hpp"

namespace bhnsid::cli {

namespace fs = std::filesystem;

namespace {

constexpr const char* record_name = ".bhnsid-plots";
constexpr const char* record_header = "bhnsid plot record 1";
constexpr std::size_t max_record_bytes = 1 << 20;

/// Control characters as \xNN: an error stays one line whatever the folder is called.
std::string printable(const std::string& text) {
  std::string out;
  for (const unsigned char c : text)
    out += (c < 0x20 || c == 0x7f) ? fmt::format("\\x{:02x}", c) : std::string(1, static_cast<char>(c));
  return out;
}

std::string shown(const fs::path& p) { return printable(p.string()); }

/// A picture's name as a script may give it: plain, visible, one line.
bool plain_name(const std::string& name) {
  if (name.empty() || name[0] == '.' || name.size() > 200) return false;
  return std::all_of(name.begin(), name.end(), [](unsigned char c) { return std::isalnum(c) || c == '.' || c == '_' || c == '-'; });
}

volatile std::sig_atomic_t stop_signal = 0;
volatile pid_t running_child = 0;

extern "C" void pass_stop_on(int sig) {
  if (stop_signal == 0) stop_signal = sig;
  const pid_t child = running_child;
  if (child > 0) ::kill(child, sig);
}

/// While plot runs, a stopping signal is passed to the script (in its own process group, so a
/// terminal's Ctrl-C reaches it once, through us) and plot then stops, tidying its staging folder.
class StopSignals {
 public:
  StopSignals() {
    struct sigaction on {};
    on.sa_handler = pass_stop_on;
    sigemptyset(&on.sa_mask);
    for (int i = 0; i < 3; ++i) {
      sigaction(signals_[i], nullptr, &old_[i]);
      if (old_[i].sa_handler != SIG_IGN) sigaction(signals_[i], &on, nullptr);  // nohup stays nohup
    }
  }
  ~StopSignals() {
    for (int i = 0; i < 3; ++i) sigaction(signals_[i], &old_[i], nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  const int signals_[3] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction old_[3] {};
};

/// Runs argv (no shell: the paths are passed as they are); the exit status, 128 + N when killed by
/// signal N, or -1 if it did not start.
int run_process(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    ::setpgid(0, 0);
    execvp(args[0], args.data());
    _exit(127);
  }
  ::setpgid(pid, pid);
  running_child = pid;
  if (stop_signal != 0) ::kill(pid, stop_signal);  // arrived between fork and here
  int status = 0;
  pid_t r = 0;
  while ((r = waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
  }
  running_child = 0;
  if (r < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// The names plot wrote in `out` before, from its record; none when there is no record.
std::set<std::string> read_record(const fs::path& out) {
  const fs::path path = out / record_name;
  std::set<std::string> names;
  if (!core::require_own_entry(path, core::EntryKind::regular_file)) return names;
  const int fd = core::open_own_file_for_reading(path, "bhnsid plot's record");
  std::string text;
  char buffer[8192];
  ssize_t n = 0;
  while ((n = ::read(fd, buffer, sizeof buffer)) > 0 && text.size() <= max_record_bytes)
    text.append(buffer, static_cast<std::size_t>(n));
  ::close(fd);
  const auto foreign = [&] {
    return core::InputError(fmt::format("{}: is not bhnsid plot's record of the pictures it wrote (expected a first "
                                        "line '{}' and one plain file name a line): move it away",
                                        shown(path), record_header));
  };
  if (n < 0 || text.size() > max_record_bytes) throw foreign();
  std::size_t start = 0, line = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string entry = text.substr(start, end - start);
    start = end + 1;
    if (line++ == 0) {
      if (entry != record_header) throw foreign();
    } else if (!entry.empty()) {
      if (!plain_name(entry)) throw foreign();
      names.insert(entry);
    }
  }
  if (line == 0) throw foreign();
  return names;
}

void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

/// The record, written under a fresh name (O_EXCL), fsynced and renamed over the old one.
void write_record(const fs::path& out, const std::set<std::string>& names) {
  std::string text = std::string(record_header) + "\n";
  for (const std::string& n : names) text += n + "\n";
  std::string temporary = (out / ".bhnsid-plots.XXXXXX").string();
  const int fd = ::mkostemp(temporary.data(), O_CLOEXEC);
  if (fd < 0) throw core::InputError(fmt::format("{}: cannot write the record of the pictures: {}", shown(out), std::strerror(errno)));
  ::fchmod(fd, 0644);
  bool ok = true;
  for (std::size_t done = 0; ok && done < text.size();) {
    const ssize_t w = ::write(fd, text.data() + done, text.size() - done);
    if (w < 0 && errno == EINTR) continue;
    ok = w > 0;
    if (ok) done += static_cast<std::size_t>(w);
  }
  ok = ok && ::fsync(fd) == 0;
  const int error = errno;
  ok = ::close(fd) == 0 && ok;
  if (!ok || ::rename(temporary.c_str(), (out / record_name).c_str()) != 0) {
    const int e = ok ? errno : error;
    ::unlink(temporary.c_str());
    throw core::InputError(fmt::format("{}: cannot write the record of the pictures: {}", shown(out / record_name),
                                       std::strerror(e)));
  }
}

/// A fresh private folder inside the output folder for the scripts to write into; removed with all
/// it holds (it is ours alone) when plot ends, however it ends.
class Staging {
 public:
  explicit Staging(const fs::path& out) {
    std::string name = (out / ".plot-XXXXXX").string();
    if (!::mkdtemp(name.data()))
      throw core::InputError(fmt::format("{}: cannot create a folder for the pictures: {}", shown(out), std::strerror(errno)));
    path_ = name;
  }
  ~Staging() {
    std::error_code ec;
    fs::remove_all(path_, ec);  // never follows a link inside it
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

struct Picture {
  std::string name;
  bool replaces = false;  // a picture of plot's own is there already
};

/// What the scripts left in the staging folder, each checked against what is at its final name.
std::vector<Picture> pictures_to_move(const fs::path& staging, const fs::path& out, const std::set<std::string>& record) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(staging)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  std::vector<Picture> pictures;
  for (const std::string& name : names) {
    struct stat st {};
    if (name[0] == '.' || ::lstat((staging / name).c_str(), &st) != 0) continue;  // a script's own temporary
    if (!S_ISREG(st.st_mode) || !plain_name(name)) {
      std::fprintf(stderr, "plot: warning: a plot script left %s, not a picture of a plain name; not kept\n",
                   printable(name).c_str());
      continue;
    }
    const fs::path target = out / name;
    Picture p{name};
    if (core::require_own_entry(target, core::EntryKind::regular_file)) {  // refuses a link, a FIFO, a folder
      if (!record.count(name))
        throw core::InputError(fmt::format("{}: exists and bhnsid plot did not write it (it is not in {}); move it "
                                           "away or choose another --output",
                                           shown(target), shown(out / record_name)));
      p.replaces = true;
    }
    pictures.push_back(p);
  }
  return pictures;
}

void move_picture(const fs::path& staging, const fs::path& out, const Picture& p) {
  const fs::path from = staging / p.name, to = out / p.name;
  int rc = 0;
  if (p.replaces) {
    rc = ::rename(from.c_str(), to.c_str());
  } else {
    // The name was free when checked: it must still be, or the picture is not ours to replace.
    rc = ::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE);
    if (rc != 0 && (errno == EINVAL || errno == ENOSYS)) {  // a file system without it
      rc = ::link(from.c_str(), to.c_str());
      if (rc == 0) ::unlink(from.c_str());
    }
  }
  if (rc != 0)
    throw core::InputError(fmt::format("{}: cannot put the picture in place: {}", shown(to),
                                       errno == EEXIST ? "something else appeared at that name meanwhile" : std::strerror(errno)));
}

}  // namespace

int cmd_plot(const std::string& run_dir, const std::string& output, const CommonOptions& common) {
  if (run_dir.empty()) throw core::InputError("plot: expected a run directory, got an empty string");
  const fs::path run(run_dir);
  if (!fs::is_regular_file(run / "params.yaml"))
    throw core::InputError(fmt::format("{}: not a run directory (no params.yaml); expected the directory of a "
                                       "`bhnsid run`",
                                       printable(run_dir)));
  const core::ParFile file = core::load_parfile(run / "params.yaml");
  core::PluginLoader loader(core::plugin_search_path(common.plugin_dirs));
  std::vector<std::pair<std::string, fs::path>> scripts;
  for (const std::string& name : file.plugins) {
    const auto found = loader.available().find(name);
    if (found == loader.available().end()) continue;
    const fs::path script = found->second.parent_path() / (name + ".plot.py");
    if (fs::exists(script)) scripts.emplace_back(name, script);
  }
  if (scripts.empty())
    throw core::InputError(fmt::format("{}: none of the run's plugins ({}) ships a plot script", printable(run_dir),
                                       fmt::join(file.plugins, ", ")));

  const fs::path out = output.empty() ? run / "plots" : fs::path(output);
  const bool created = !core::require_own_entry(out, core::EntryKind::folder);
  // The folders above `out` that plot makes, outermost last: removed again with it when no picture comes.
  std::vector<fs::path> made;
  if (created) {
    fs::path start = out.lexically_normal();
    if (!start.has_filename() && start.has_parent_path()) start = start.parent_path();  // "a/b/" names a/b
    for (fs::path p = start; !p.empty() && p != p.parent_path() && !fs::exists(p); p = p.parent_path())
      made.push_back(p);
    fs::create_directories(out);
  }
  const std::set<std::string> record = read_record(out);
  // Debian's interpreter, where matplotlib and h5py are installed (scripts/install-deps.sh).
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  StopSignals signals;
  std::optional<Staging> staging(std::in_place, out);
  // A folder made for pictures that never came is removed again (rmdir: only when empty).
  const auto tidy = [&] {
    staging.reset();
    for (const fs::path& p : made)
      if (::rmdir(p.c_str()) != 0) break;  // not empty: something else lives there now
  };
  int failed = 0, bad_input = 0;
  for (const auto& [name, script] : scripts) {
    std::printf("plot: %s\n", name.c_str());
    std::fflush(stdout);
    std::set<fs::path> before;
    for (const auto& entry : fs::directory_iterator(staging->path())) before.insert(entry.path());
    const int code = run_process({python, script.string(), run.string(), staging->path().string()});
    if (stop_signal != 0) {
      tidy();
      std::fprintf(stderr, "plot: stopped by %s; no picture was moved into %s\n", core::signal_name(stop_signal), shown(out).c_str());
      return 128 + stop_signal;
    }
    if (code == core::exit_input) {
      ++bad_input;  // the script has said which file and why, in one line
    } else if (code != 0) {
      ++failed;
      std::fprintf(stderr, "plot: %s's plot script (%s) failed with status %d\n", name.c_str(), shown(script).c_str(), code);
    }
    if (code != 0) {  // half of a failed script's pictures would pass for a complete set
      std::vector<fs::path> left;
      for (const auto& entry : fs::directory_iterator(staging->path()))
        if (!before.count(entry.path())) left.push_back(entry.path());
      for (const fs::path& p : left) fs::remove_all(p);
    }
  }
  const std::vector<Picture> pictures = pictures_to_move(staging->path(), out, record);
  std::set<std::string> written = record;
  for (const Picture& p : pictures) written.insert(p.name);
  // The record first: a picture in place is then always listed as plot's own.
  if (!pictures.empty()) write_record(out, written);
  for (const Picture& p : pictures) move_picture(staging->path(), out, p);
  const int succeeded = static_cast<int>(scripts.size()) - failed - bad_input;
  if (pictures.empty()) {
    tidy();
    std::printf("plot: %d of %zu plot script(s) succeeded; no picture written\n", succeeded, scripts.size());
  } else {
    staging.reset();
    sync_folder(out);
    std::printf("plot: %d of %zu plot script(s) succeeded; pictures in %s\n", succeeded, scripts.size(), shown(out).c_str());
  }
  if (bad_input > 0) return core::exit_input;
  return failed == 0 ? core::exit_ok : core::exit_run_failed;
}

}  // namespace bhnsid::cli
