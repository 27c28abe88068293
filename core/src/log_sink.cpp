#include "log_sink.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <unistd.h>

#include "bhnsid/core/atomic_file.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/log.hpp"

namespace bhnsid::core {

LogSink::~LogSink() {
  if (file_) std::fclose(file_);
}

void LogSink::open_file(const std::filesystem::path& partial, bool append, const std::filesystem::path& final_path) {
  std::error_code ec;
  if (append && !std::filesystem::exists(partial, ec) && !final_path.empty() && std::filesystem::exists(final_path, ec))
    std::filesystem::copy_file(final_path, partial, ec);
  file_ = std::fopen(partial.c_str(), append ? "a" : "w");
  if (!file_) throw InputError(fmt::format("{}: cannot create the log: {}", partial.string(), std::strerror(errno)));
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
