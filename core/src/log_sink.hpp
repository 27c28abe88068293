#pragma once
// Where Log lines go: the terminal (info to stdout, warnings to stderr) and, during a run, the
// run directory's log.txt.partial, renamed to log.txt when the run ends.
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <string>

namespace bhnsid::core {

class LogSink {
 public:
  LogSink() = default;
  LogSink(const LogSink&) = delete;
  LogSink& operator=(const LogSink&) = delete;
  ~LogSink();

  /// `append`: a resumed run continues the earlier run's log (the partial one a kill left, or
  /// `final_path` of one that ended), so that one log.txt tells the whole story.
  void open_file(const std::filesystem::path& partial, bool append = false, const std::filesystem::path& final_path = {});
  enum class Level { info, warning, detail };
  void write(Level level, const std::string& prefix, const std::string& message);
  /// Detail lines reach the terminal too.
  void set_verbose(bool verbose) { verbose_ = verbose; }
  /// Closes the file and renames it to `final_path`; InputError if any write to it failed.
  void finish(const std::filesystem::path& final_path);
  /// Closes and removes the partial log (the run never started).
  void abandon();

 private:
  std::mutex mutex_;
  std::FILE* file_ = nullptr;
  std::filesystem::path partial_;
  bool failed_ = false;
  bool verbose_ = false;
};

}  // namespace bhnsid::core
