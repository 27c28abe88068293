#include "log_sink.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

#include "bhnsid/core/atomic_file.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/log.hpp"
#include "bhnsid/core/owned_entry.hpp"

namespace bhnsid::core {

LogSink::~LogSink() {
  if (file_) std::fclose(file_);
}

namespace {

// Appends the earlier run's final log to the fresh partial one (a resume after a finished run).
void copy_into(int fd, const std::filesystem::path& from) {
  const int in = open_own_file_for_reading(from, "the log");
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(in, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    for (ssize_t done = 0; done < n;) {
      const ssize_t w = ::write(fd, buffer + done, static_cast<std::size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w < 0) {
        const int error = errno;
        ::close(in);
        throw InputError(fmt::format("{}: cannot copy the earlier log: {}", from.string(), std::strerror(error)));
      }
      done += w;
    }
  }
  ::close(in);
}

}  // namespace

void LogSink::open_file(const std::filesystem::path& partial, bool append, const std::filesystem::path& final_path) {
  int fd = -1;
  if (append && require_own_entry(partial, EntryKind::regular_file)) {
    fd = open_own_file_for_appending(partial);
  } else {
    fd = create_fresh_file(partial);
    try {
      if (append && !final_path.empty() && require_own_entry(final_path, EntryKind::regular_file)) copy_into(fd, final_path);
    } catch (...) {
      ::close(fd);
      throw;
    }
  }
  file_ = ::fdopen(fd, append ? "a" : "w");
  if (!file_) {
    const int error = errno;
    ::close(fd);
    throw InputError(fmt::format("{}: cannot create the log: {}", partial.string(), std::strerror(error)));
  }
  partial_ = partial;
}

void LogSink::write(Level level, const std::string& prefix, const std::string& message) {
  const bool warning = level == Level::warning;
  const std::string line = (prefix.empty() ? "" : "[" + prefix + "] ") + (warning ? "warning: " : "") + message + "\n";
  std::lock_guard<std::mutex> lock(mutex_);
  if (level != Level::detail || verbose_) {
    std::fputs(line.c_str(), warning ? stderr : stdout);
    std::fflush(warning ? stderr : stdout);
  }
  if (file_ && !failed_) {
    // Flushed per line so that a long run's progress can be followed with tail -f.
    if (std::fputs(line.c_str(), file_) < 0 || std::fflush(file_) != 0) failed_ = true;
  }
}

void LogSink::finish(const std::filesystem::path& final_path) {
  if (!file_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed_ || close_failed)
    throw InputError(fmt::format("{}: writing the log failed (disk full?); the partial log is kept", partial_.string()));
  commit_file(partial_, final_path);
}

void LogSink::abandon() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (file_) std::fclose(file_);
  file_ = nullptr;
  if (!partial_.empty()) ::unlink(partial_.c_str());
}

void Log::info(const std::string& message) const {
  if (sink_) sink_->write(LogSink::Level::info, prefix_, message);
}
void Log::warn(const std::string& message) const {
  if (sink_) sink_->write(LogSink::Level::warning, prefix_, message);
}
void Log::detail(const std::string& message) const {
  if (sink_) sink_->write(LogSink::Level::detail, prefix_, message);
}

}  // namespace bhnsid::core
