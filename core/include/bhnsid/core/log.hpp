#pragma once
// Everything printed goes through the Log: to the terminal and to the run directory's log.txt.
#include <fmt/format.h>

#include <string>

namespace bhnsid::core {

class LogSink;

class Log {
 public:
  Log(LogSink* sink, std::string prefix) : sink_(sink), prefix_(std::move(prefix)) {}

  void info(const std::string& message) const;
  void warn(const std::string& message) const;
  /// To log.txt always, to the terminal only with `bhnsid run --verbose`: the per-cycle and
  /// per-step lines of a long run, where the terminal shows one line per iteration.
  void detail(const std::string& message) const;

  template <class... Args>
  void info(fmt::format_string<Args...> format, Args&&... args) const {
    info(fmt::format(format, std::forward<Args>(args)...));
  }
  template <class... Args>
  void warn(fmt::format_string<Args...> format, Args&&... args) const {
    warn(fmt::format(format, std::forward<Args>(args)...));
  }
  template <class... Args>
  void detail(fmt::format_string<Args...> format, Args&&... args) const {
    detail(fmt::format(format, std::forward<Args>(args)...));
  }

 private:
  LogSink* sink_;
  std::string prefix_;
};

}  // namespace bhnsid::core
