#pragma once
// Shared by the CLI tests: a temp folder with a parameter file, and bhnsid run against the test plugins.
#include <string>
#include <vector>

#include "process.hpp"

namespace bhnsid::test {

inline ProcessResult bhnsid_with_test_plugins(std::vector<std::string> args, const std::filesystem::path& cwd = {},
                                              long file_size_limit = 0) {
  args.push_back("--plugin-path");
  args.push_back(test_plugin_dir().string());
  return run_bhnsid(args, cwd, file_size_limit);
}

/// bhnsid run PARFILE --output OUT EXTRA... against the test plugins.
inline ProcessResult run_parfile_with_test_plugins(const std::filesystem::path& parfile, const std::filesystem::path& out,
                                                   std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"run", parfile.string(), "--output", out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return bhnsid_with_test_plugins(args);
}

/// A minimal valid parameter file for tp_counter (+ extra YAML appended).
inline std::string counter_parfile(const std::string& extra = "") {
  return "plugins: [tp_counter]\ntp_counter:\n  needed: 2.0\n" + extra;
}

/// The number of lines in stderr: bad input must give exactly one.
inline int line_count(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

}  // namespace bhnsid::test
