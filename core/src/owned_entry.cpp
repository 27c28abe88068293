#include "bhnsid/core/owned_entry.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::core {

namespace fs = std::filesystem;

namespace {

const char* describe_mode(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISREG(mode)) return "a regular file";
  return "an entry of unknown type";
}

[[noreturn]] void refuse(const fs::path& path, mode_t mode, EntryKind kind) {
  throw InputError(fmt::format("{}: is {}, where bhnsid writes {} of its own; it never writes through, reads from or "
                               "deletes inside such an entry: move it away",
                               path.string(), describe_mode(mode),
                               kind == EntryKind::folder ? "a folder" : "a regular file"));
}

}  // namespace

bool require_own_entry(const fs::path& path, EntryKind kind) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return false;
    throw InputError(fmt::format("{}: cannot be examined: {}", path.string(), std::strerror(errno)));
  }
  const bool fits = kind == EntryKind::folder ? S_ISDIR(st.st_mode) : S_ISREG(st.st_mode);
  if (!fits) refuse(path, st.st_mode, kind);
  return true;
}

int create_fresh_file(const fs::path& path) {
  if (require_own_entry(path, EntryKind::regular_file) && ::unlink(path.c_str()) != 0 && errno != ENOENT)
    throw InputError(fmt::format("{}: cannot remove the unfinished file of an earlier run: {}", path.string(),
                                 std::strerror(errno)));
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0)
    throw InputError(fmt::format("{}: cannot create the file: {}", path.string(),
                                 errno == EEXIST ? "another process made an entry of that name meanwhile"
                                                 : std::strerror(errno)));
  return fd;
}

namespace {

// Opens a regular file of ours with `access` flags, never through a link and never waiting on a
// FIFO (O_NONBLOCK, then fstat; the flag is cleared again); `st` receives its status.
int open_own_regular(const fs::path& path, int access, const std::string& what, struct stat& st) {
  const int fd = ::open(path.c_str(), access | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    struct stat link {};
    if (error == ELOOP && ::lstat(path.c_str(), &link) == 0) refuse(path, link.st_mode, EntryKind::regular_file);
    throw InputError(fmt::format("{}: cannot open {}: {}", path.string(), what, std::strerror(error)));
  }
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    const mode_t mode = st.st_mode;
    ::close(fd);
    refuse(path, mode, EntryKind::regular_file);
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
}

}  // namespace

int open_own_file_for_appending(const fs::path& path) {
  struct stat st {};
  const int fd = open_own_regular(path, O_WRONLY | O_APPEND, "it to append", st);
  if (st.st_nlink != 1) {
    ::close(fd);
    throw InputError(fmt::format("{}: has {} names (a hard link to another file); bhnsid appends only to a file of its "
                                 "own: move it away",
                                 path.string(), st.st_nlink));
  }
  return fd;
}

int open_own_file_for_reading(const fs::path& path, const std::string& what) {
  struct stat st {};
  return open_own_regular(path, O_RDONLY, what, st);
}

}  // namespace bhnsid::core
