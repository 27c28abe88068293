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
};

/// Runs build/bin/bhnsid with `args`; `file_size_limit` > 0 sets RLIMIT_FSIZE in the child to
/// simulate a full disk.
ProcessResult run_bhnsid(const std::vector<std::string>& args, const std::filesystem::path& cwd = {},
                         long file_size_limit = 0);

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
