#pragma once
// Helpers for tests that drive the bhnsid executable as a user would.
#include <filesystem>
#include <string>
#include <vector>

namespace bhnsid::test {

struct ProcessResult {
  int exit_code = -1;  ///< -1 when the process was killed by a signal
  int signal = 0;
  std::string out, err;
  long max_rss_kib = 0;  ///< peak resident size of the child
  double seconds = 0;    ///< wall time from start to exit
};

/// How the child's standard output is connected.
enum class Stdout { captured, closed_pipe, dev_full };

/// bhnsid running in the background (concurrent runs, signals); killed if still running when destroyed.
class Background {
 public:
  explicit Background(const std::vector<std::string>& args, const std::filesystem::path& cwd = {});
  ~Background();
  Background(const Background&) = delete;
  Background& operator=(const Background&) = delete;
  int pid() const { return pid_; }
  void signal(int sig) const;
  /// Waits at most `timeout_seconds`; a child still running then is killed (SIGKILL) and reported so.
  ProcessResult wait(double timeout_seconds = 60);

 private:
  int pid_ = -1;
  std::filesystem::path capture_;
  double start_ = 0;
};

/// Polls until `path` exists and contains `text` (empty: exists), at most `timeout_seconds`.
bool wait_for_text(const std::filesystem::path& path, const std::string& text, double timeout_seconds = 30);

/// Runs build/bin/bhnsid with `args`; `file_size_limit` > 0 sets RLIMIT_FSIZE in the child to
/// simulate a full disk.
ProcessResult run_bhnsid(const std::vector<std::string>& args, const std::filesystem::path& cwd = {},
                         long file_size_limit = 0, Stdout out = Stdout::captured);

/// The same for another executable (a copy of bhnsid elsewhere, a tool beside it).
ProcessResult run_program(const std::filesystem::path& program, const std::vector<std::string>& args,
                          const std::filesystem::path& cwd = {}, long file_size_limit = 0, Stdout out = Stdout::captured);

/// A fresh empty directory under the system temp folder, removed when the object goes.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path write(const std::string& name, const std::string& contents) const;

 private:
  std::filesystem::path path_;
};

std::string read_file(const std::filesystem::path& path);
std::filesystem::path source_dir();
std::filesystem::path test_plugin_dir();

}  // namespace bhnsid::test
