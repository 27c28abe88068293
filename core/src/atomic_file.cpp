#include "bhnsid/core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/owned_entry.hpp"

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
  // A link, FIFO or folder at the final name is not ours to replace (the rename would drop it silently).
  require_own_entry(path, EntryKind::regular_file);
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
  require_own_entry(to, EntryKind::regular_file);
  const int fd = ::open(from.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  if (::rename(from.c_str(), to.c_str()) != 0) fail(to, "rename the finished file into place", errno);
  fsync_directory(to.parent_path());
}

}  // namespace bhnsid::core
