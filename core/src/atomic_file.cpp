#include "bhnsid/core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::core {

namespace fs = std::filesystem;

namespace {
void fsync_directory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

[[noreturn]] void fail(const fs::path& path, const char* what, int error) {
  throw InputError(fmt::format("{}: cannot {}: {}", path.string(), what, std::strerror(error)));
}
}  // namespace

void write_file_atomic(const fs::path& path, const std::string& contents) {
  std::string temp = path.string() + ".tmp.XXXXXX";
  const int fd = ::mkstemp(temp.data());
  if (fd < 0) fail(path, "create a temporary file for writing", errno);
  const auto abandon = [&](const char* what, int error) {
    ::close(fd);
    ::unlink(temp.c_str());
    fail(path, what, error);
  };
  const char* data = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      abandon("write", errno);
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fchmod(fd, 0644) != 0) abandon("set permissions", errno);
  if (::fsync(fd) != 0) abandon("flush to disk", errno);
  if (::close(fd) != 0) {
    ::unlink(temp.c_str());
    fail(path, "close", errno);
  }
  if (::rename(temp.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(temp.c_str());
    fail(path, "rename the finished file into place", error);
  }
  fsync_directory(path.parent_path());
}

void commit_file(const fs::path& from, const fs::path& to) {
  const int fd = ::open(from.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  if (::rename(from.c_str(), to.c_str()) != 0) fail(to, "rename the finished file into place", errno);
  fsync_directory(to.parent_path());
}

void prepare_run_directory(const fs::path& dir, bool force) {
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!force)
      throw InputError(fmt::format("{}: the run directory exists; choose another with --output DIR or replace it with "
                                   "--force",
                                   dir.string()));
    const bool looks_like_run = fs::is_directory(dir, ec) &&
                                (fs::exists(dir / "params.yaml", ec) || fs::exists(dir / "summary.json", ec) ||
                                 fs::exists(dir / "log.txt.partial", ec) || fs::is_empty(dir, ec));
    if (!looks_like_run)
      throw InputError(fmt::format("{}: exists and is not a bhnsid run directory; --force only replaces run "
                                   "directories",
                                   dir.string()));
    fs::remove_all(dir, ec);
    if (ec) throw InputError(fmt::format("{}: cannot remove the old run directory: {}", dir.string(), ec.message()));
  }
  fs::create_directories(dir, ec);
  if (ec) throw InputError(fmt::format("{}: cannot create the run directory: {}", dir.string(), ec.message()));
  // Root ignores permission bits, so probe by writing rather than by inspecting modes.
  std::string probe = (dir / ".write-probe.XXXXXX").string();
  const int fd = ::mkstemp(probe.data());
  if (fd < 0) fail(dir, "write into the run directory", errno);
  const bool wrote = ::write(fd, "x", 1) == 1;
  const int error = errno;
  ::close(fd);
  ::unlink(probe.c_str());
  if (!wrote) fail(dir, "write into the run directory", error);
}

}  // namespace bhnsid::core
