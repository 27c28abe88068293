#include "export_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>

namespace bhnsid::exporter {

namespace {

const char* describe(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return "not a regular file";
}

std::string at_line(const std::string& path, std::size_t line) { return path + ":" + std::to_string(line) + ": "; }

/// One coordinate: decimal notation only (no hex, nan or inf), and finite.
double coordinate(const std::string& word, const std::string& where) {
  const bool decimal = word.find_first_not_of("0123456789+-.eE") == std::string::npos;
  char* end = nullptr;
  const double d = decimal ? std::strtod(word.c_str(), &end) : 0.0;
  if (!decimal || end != word.c_str() + word.size())
    throw BadInput{where + "'" + word + "' is not a number (expected x y z in decimal notation)"};
  if (!std::isfinite(d)) throw BadInput{where + "'" + word + "' overflows a double"};
  return d;
}

// The temporary being written, for the signal handler: removed if the program is stopped.
char pending[4096];
volatile std::sig_atomic_t pending_set = 0;

extern "C" void remove_pending_and_stop(int sig) {
  if (pending_set) ::unlink(pending);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

/// Owns the temporary: removes it unless released, and while it exists a stop signal removes it too.
class Temporary {
 public:
  explicit Temporary(const std::string& path) : path_(path) {
    if (path.size() < sizeof pending) {
      std::memcpy(pending, path.c_str(), path.size() + 1);
      pending_set = 1;
    }
    struct sigaction on {};
    on.sa_handler = remove_pending_and_stop;
    sigemptyset(&on.sa_mask);
    for (int i = 0; i < 3; ++i) {
      sigaction(signals_[i], nullptr, &old_[i]);
      // A signal ignored at start (nohup) stays ignored.
      if (old_[i].sa_handler != SIG_IGN) sigaction(signals_[i], &on, nullptr);
    }
  }
  ~Temporary() {
    if (!released_) ::unlink(path_.c_str());
    pending_set = 0;
    for (int i = 0; i < 3; ++i) sigaction(signals_[i], &old_[i], nullptr);
  }
  Temporary(const Temporary&) = delete;
  Temporary& operator=(const Temporary&) = delete;
  void release() { released_ = true; }

 private:
  std::string path_;
  bool released_ = false;
  const int signals_[3] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction old_[3] {};
};

void sync_folder(const std::string& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);  // best effort: the file itself is already on disk
  ::close(fd);
}

}  // namespace

std::string printable(const std::string& text) {
  std::string out;
  const auto escape = [&](unsigned char c) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "\\x%02x", c);
    out += hex;
  };
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    // A well-formed UTF-8 sequence is kept; a stray byte of a damaged file's string is escaped.
    const std::size_t length = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
    bool whole = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; whole && k < length; ++k) whole = (static_cast<unsigned char>(text[i + k]) >> 6) == 0x2;
    if (!whole || c < 0x20 || c == 0x7f) {
      escape(c);
      ++i;
    } else {
      out.append(text, i, length);
      i += length;
    }
  }
  return out;
}

Points read_points(const std::string& path) {
  // Non-blocking, then fstat: a FIFO or a device is refused before a byte is read from it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw BadInput{"cannot read the points file " + path + ": " + std::strerror(errno)};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    const mode_t mode = st.st_mode;
    ::close(fd);
    throw BadInput{path + ": the points file is " + describe(mode) + ", not a regular file"};
  }
  const auto too_large = [&] {
    return BadInput{path + ": the points file is larger than " + std::to_string(max_points_file_bytes >> 20) +
                    " MiB (at most " + std::to_string(max_points) + " points)"};
  };
  if (static_cast<unsigned long long>(st.st_size) > max_points_file_bytes) {
    ::close(fd);
    throw too_large();
  }
  std::string text;
  char buffer[65536];
  while (true) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      ::close(fd);
      throw BadInput{"error while reading the points file " + path + ": " + std::strerror(e)};
    }
    if (n == 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    if (text.size() > max_points_file_bytes) {  // grew while being read
      ::close(fd);
      throw too_large();
    }
  }
  ::close(fd);

  Points p;
  std::size_t number = 0;
  for (std::size_t start = 0; start < text.size();) {
    ++number;
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (end - start > max_points_line)
      throw BadInput{at_line(path, number) + "a line of more than " + std::to_string(max_points_line) +
                     " characters (expected x y z)"};
    std::string line = text.substr(start, end - start);
    start = end + 1;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::vector<double> v;
    for (std::size_t i = 0; i < line.size();) {
      const std::size_t first = line.find_first_not_of(" \t\r\v\f", i);
      if (first == std::string::npos) break;
      std::size_t last = line.find_first_of(" \t\r\v\f", first);
      if (last == std::string::npos) last = line.size();
      v.push_back(coordinate(line.substr(first, last - first), at_line(path, number)));
      i = last;
    }
    if (v.empty()) continue;
    if (v.size() != 3)
      throw BadInput{at_line(path, number) + "expected three numbers x y z, found " + std::to_string(v.size())};
    if (p.x.size() == max_points)
      throw BadInput{at_line(path, number) + "more than " + std::to_string(max_points) + " points"};
    p.x.push_back(v[0]);
    p.y.push_back(v[1]);
    p.z.push_back(v[2]);
  }
  return p;
}

void check_output(const std::string& output, bool force, const std::vector<std::string>& inputs) {
  if (output.empty()) throw BadInput{"--output needs a file name"};
  if (output.back() == '/') throw BadInput{"--output " + output + " names a folder; expected a file name"};
  struct stat st {};
  if (::lstat(output.c_str(), &st) == 0) {
    if (!force) throw BadInput{output + " exists; pass --force to replace it"};
    if (!S_ISREG(st.st_mode))
      throw BadInput{output + " is " + describe(st.st_mode) +
                     "; --force replaces only a regular file, and never writes through a link"};
    for (const std::string& input : inputs) {
      struct stat in {};
      if (::stat(input.c_str(), &in) == 0 && in.st_dev == st.st_dev && in.st_ino == st.st_ino)
        throw BadInput{output + " is the input file " + input + "; --force would replace it by the table"};
    }
  } else if (errno != ENOENT) {
    throw BadInput{"cannot examine --output " + output + ": " + std::strerror(errno)};
  }
  const std::size_t slash = output.rfind('/');
  const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : output.substr(0, slash);
  if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw BadInput{"cannot write " + output + ": its folder " + folder + " does not exist"};
}

void write_output(const std::string& output, bool force, const std::function<void(std::FILE*)>& write) {
  const std::size_t slash = output.rfind('/');
  const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : output.substr(0, slash);
  const std::string base = slash == std::string::npos ? output : output.substr(slash + 1);
  // A hidden name of our own, never OUT.partial: a user's file of that name is not ours to touch.
  std::string name = folder + "/." + base.substr(0, 200) + ".partial-XXXXXX";
  const int fd = ::mkostemp(name.data(), O_CLOEXEC);  // O_CREAT | O_EXCL: never an existing entry
  if (fd < 0) throw BadInput{"cannot write " + output + ": " + std::strerror(errno)};
  Temporary temporary(name);
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);  // as an ordinary new file, not mkstemp's 0600
  std::FILE* f = ::fdopen(fd, "w");
  if (!f) {
    const int e = errno;
    ::close(fd);
    throw BadInput{"cannot write " + output + ": " + std::strerror(e)};
  }
  write(f);
  bool ok = std::fflush(f) == 0 && !std::ferror(f) && ::fsync(::fileno(f)) == 0;
  const int saved = errno;
  ok = std::fclose(f) == 0 && ok;
  if (!ok) throw BadInput{"cannot write " + output + ": " + std::strerror(saved ? saved : errno)};
  if (force) {
    if (std::rename(name.c_str(), output.c_str()) != 0)
      throw BadInput{"cannot move the table to " + output + ": " + std::strerror(errno)};
  } else {
    // Without --force the final step must fail if the name appeared meanwhile: rename would replace it.
    int rc = ::renameat2(AT_FDCWD, name.c_str(), AT_FDCWD, output.c_str(), RENAME_NOREPLACE);
    if (rc != 0 && (errno == EINVAL || errno == ENOSYS)) {  // a file system without it: link, then unlink
      rc = ::link(name.c_str(), output.c_str());
      if (rc == 0) ::unlink(name.c_str());
    }
    if (rc != 0)
      throw BadInput{errno == EEXIST ? output + " exists; pass --force to replace it"
                                     : "cannot create " + output + ": " + std::strerror(errno)};
  }
  temporary.release();
  sync_folder(folder);
}

}  // namespace bhnsid::exporter
