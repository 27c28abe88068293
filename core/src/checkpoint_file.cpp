#include "checkpoint_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "bhnsid/core/atomic_file.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/owned_entry.hpp"

namespace bhnsid::core {

namespace fs = std::filesystem;

namespace {
constexpr char magic[8] = {'B', 'H', 'N', 'S', 'I', 'D', 'C', 'K'};
// One name or string longer than this is no checkpoint of ours: a damaged length field.
constexpr std::uint32_t longest_name = 4096;

const char* type_name(char type) {
  switch (type) {
    case 'd': return "doubles";
    case 'i': return "integers";
    case 's': return "a string";
    default: return "bytes";
  }
}
}  // namespace

std::uint64_t fnv1a(std::uint64_t hash, const void* bytes, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(bytes);
  for (std::size_t i = 0; i < n; ++i) {
    hash ^= p[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

void Checksum::add(const void* bytes, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(bytes);
  count_ += n;
  while (n > 0 && tail_size_ > 0) {
    tail_[tail_size_++] = *p++;
    --n;
    if (tail_size_ == 8) {
      std::uint64_t w;
      std::memcpy(&w, tail_, 8);
      word(w);
      tail_size_ = 0;
    }
  }
  for (; n >= 8; n -= 8, p += 8) {
    std::uint64_t w;
    std::memcpy(&w, p, 8);
    word(w);
  }
  for (; n > 0; --n) tail_[tail_size_++] = *p++;
}

std::uint64_t Checksum::value() const {
  Checksum last = *this;
  if (last.tail_size_ > 0) {
    std::uint64_t w = 0;
    std::memcpy(&w, last.tail_, last.tail_size_);
    last.word(w);
  }
  last.word(count_);
  return last.hash_;
}

std::vector<double> CheckpointReader::reals(const std::string& name) const {
  std::vector<double> v(size(name, 'd') / sizeof(double));
  get(name, v.data(), v.size());
  return v;
}

std::vector<std::int64_t> CheckpointReader::integers(const std::string& name) const {
  std::vector<std::int64_t> v(size(name, 'i') / sizeof(std::int64_t));
  read(name, 'i', v.data(), v.size() * sizeof(std::int64_t));
  return v;
}

std::string CheckpointReader::string(const std::string& name) const {
  std::string s(size(name, 's'), '\0');
  read(name, 's', s.data(), s.size());
  return s;
}

CheckpointFileWriter::CheckpointFileWriter(fs::path partial) : partial_(std::move(partial)) {
  const int fd = create_fresh_file(partial_);
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int error = errno;
    ::close(fd);
    throw InputError(fmt::format("{}: cannot create the checkpoint: {}", partial_.string(), std::strerror(error)));
  }
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
  write(magic, sizeof magic);
  write(&checkpoint_format_version, sizeof checkpoint_format_version);
}

CheckpointFileWriter::~CheckpointFileWriter() {
  if (file_) std::fclose(file_);  // an unfinished write: the .partial stays for the next run to remove
}

void CheckpointFileWriter::write(const void* data, std::size_t bytes) {
  if (bytes == 0) return;
  if (std::fwrite(data, 1, bytes, file_) != bytes)
    throw InputError(fmt::format("{}: writing the checkpoint failed: {}", partial_.string(), std::strerror(errno)));
  hash_.add(data, bytes);
}

void CheckpointFileWriter::section(const std::string& name) {
  const char kind = 'S';
  const auto len = static_cast<std::uint32_t>(name.size());
  write(&kind, 1);
  write(&len, sizeof len);
  write(name.data(), name.size());
  in_section_ = true;
}

void CheckpointFileWriter::record(const std::string& name, char type, const void* data, std::size_t bytes) {
  if (!in_section_) throw std::logic_error("checkpoint entry outside a section");
  if (name.empty() || name.size() > longest_name) throw std::logic_error("checkpoint entry name of bad length: " + name);
  const char kind = 'E';
  const auto len = static_cast<std::uint32_t>(name.size());
  const auto size = static_cast<std::uint64_t>(bytes);
  write(&kind, 1);
  write(&type, 1);
  write(&len, sizeof len);
  write(name.data(), name.size());
  write(&size, sizeof size);
  write(data, bytes);
}

void CheckpointFileWriter::finish(const fs::path& final_path) {
  const char kind = 'Z';
  write(&kind, 1);
  const std::uint64_t sum = hash_.value();
  if (std::fwrite(&sum, 1, sizeof sum, file_) != sizeof sum || std::fflush(file_) != 0 || ::fsync(fileno(file_)) != 0) {
    const int error = errno;
    std::fclose(file_);
    file_ = nullptr;
    throw InputError(fmt::format("{}: writing the checkpoint failed: {}", partial_.string(), std::strerror(error)));
  }
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!closed) throw InputError(fmt::format("{}: closing the checkpoint failed: {}", partial_.string(), std::strerror(errno)));
  commit_file(partial_, final_path);
}

CheckpointFileReader::CheckpointFileReader(fs::path path) : path_(std::move(path)) {
  fd_ = open_own_file_for_reading(path_, "the checkpoint");
  std::FILE* f = ::fdopen(::dup(fd_), "rb");
  if (!f) throw InputError(fmt::format("{}: cannot read the checkpoint: {}", path_.string(), std::strerror(errno)));
  std::setvbuf(f, nullptr, _IOFBF, 1 << 20);
  Checksum hash;
  std::uint64_t offset = 0;
  const auto bad = [&](const std::string& why) {
    std::fclose(f);
    return InputError(fmt::format("{}: not a usable checkpoint: {}", path_.string(), why));
  };
  const auto take = [&](void* out, std::size_t n) {
    if (n > 0 && std::fread(out, 1, n, f) != n) throw bad(fmt::format("truncated at byte {} (a write that did not finish)", offset));
    hash.add(out, n);
    offset += n;
  };
  const auto take_name = [&]() {
    std::uint32_t len = 0;
    take(&len, sizeof len);
    if (len > longest_name) throw bad(fmt::format("a name of {} bytes at byte {}", len, offset));
    std::string name(len, '\0');
    take(name.data(), len);
    return name;
  };
  char head[sizeof magic];
  take(head, sizeof head);
  if (std::memcmp(head, magic, sizeof magic) != 0) throw bad("it does not start with BHNSIDCK");
  std::uint32_t version = 0;
  take(&version, sizeof version);
  if (version != checkpoint_format_version)
    throw bad(fmt::format("format version {}, this bhnsid reads {}", version, checkpoint_format_version));
  std::map<std::string, Entry>* current = nullptr;
  std::vector<char> buffer(1 << 20);
  for (;;) {
    char kind = 0;
    take(&kind, 1);
    if (kind == 'Z') break;
    if (kind == 'S') {
      current = &index_[take_name()];
    } else if (kind == 'E') {
      if (!current) throw bad("an entry before any section");
      Entry e;
      take(&e.type, 1);
      const std::string name = take_name();
      take(&e.bytes, sizeof e.bytes);
      e.offset = offset;
      // The data is hashed but not kept: the accessors read it again when asked.
      for (std::uint64_t left = e.bytes; left > 0;) {
        const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(left, buffer.size()));
        take(buffer.data(), n);
        left -= n;
      }
      (*current)[name] = e;
    } else {
      throw bad(fmt::format("an unknown record at byte {}", offset - 1));
    }
  }
  std::uint64_t stored = 0;
  const std::uint64_t computed = hash.value();
  take(&stored, sizeof stored);
  const bool at_end = std::fgetc(f) == EOF;
  if (stored != computed) throw bad("its checksum does not match its contents (damaged)");
  if (!at_end) throw bad("bytes after its end");
  std::fclose(f);
}

CheckpointFileReader::~CheckpointFileReader() {
  if (fd_ >= 0) ::close(fd_);
}

void CheckpointFileReader::section(const std::string& name) { section_ = name; }

std::vector<std::string> CheckpointFileReader::sections() const {
  std::vector<std::string> out;
  for (const auto& [name, entries] : index_) out.push_back(name);
  return out;
}

bool CheckpointFileReader::has(const std::string& name) const {
  auto s = index_.find(section_);
  return s != index_.end() && s->second.count(name) > 0;
}

const CheckpointFileReader::Entry& CheckpointFileReader::entry(const std::string& name, char type) const {
  const auto s = index_.find(section_);
  const bool found = s != index_.end() && s->second.count(name) > 0;
  if (!found)
    throw InputError(fmt::format("{}: plugin {} saved no entry '{}' (a checkpoint of another build of the plugin?)",
                                 path_.string(), section_, name));
  const Entry& e = s->second.at(name);
  if (e.type != type)
    throw InputError(fmt::format("{}: plugin {}'s entry '{}' holds {}, expected {}", path_.string(), section_, name,
                                 type_name(e.type), type_name(type)));
  return e;
}

std::size_t CheckpointFileReader::size(const std::string& name, char type) const {
  return static_cast<std::size_t>(entry(name, type).bytes);
}

void CheckpointFileReader::read(const std::string& name, char type, void* out, std::size_t bytes) const {
  const Entry& e = entry(name, type);
  if (e.bytes != bytes)
    throw InputError(fmt::format("{}: plugin {}'s entry '{}' holds {} bytes, this run expects {} (another grid or "
                                 "configuration?)",
                                 path_.string(), section_, name, e.bytes, bytes));
  auto* p = static_cast<char*>(out);
  for (std::size_t done = 0; done < bytes;) {
    const ssize_t n = ::pread(fd_, p + done, bytes - done, static_cast<off_t>(e.offset + done));
    if (n <= 0) throw InputError(fmt::format("{}: reading entry '{}' failed: {}", path_.string(), name, std::strerror(errno)));
    done += static_cast<std::size_t>(n);
  }
}

fs::path checkpoint_path(const fs::path& dir, int iteration) { return dir / fmt::format("checkpoint.{:06d}", iteration); }

namespace {
bool is_checkpoint_name(const std::string& name) {
  const std::string prefix = "checkpoint.";
  return name.size() == prefix.size() + 6 && name.compare(0, prefix.size(), prefix) == 0 &&
         std::all_of(name.begin() + static_cast<std::ptrdiff_t>(prefix.size()), name.end(),
                     [](char c) { return c >= '0' && c <= '9'; });
}
}  // namespace

bool is_checkpoint_entry_name(const std::string& name) {
  const std::string partial = ".partial";
  if (name.size() > partial.size() && name.compare(name.size() - partial.size(), partial.size(), partial) == 0)
    return is_checkpoint_name(name.substr(0, name.size() - partial.size()));
  return is_checkpoint_name(name);
}

std::vector<int> checkpoint_iterations(const fs::path& dir) {
  std::vector<int> out;
  std::error_code ec;
  for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (is_checkpoint_name(name)) out.push_back(std::stoi(name.substr(std::strlen("checkpoint."))));
  }
  std::sort(out.rbegin(), out.rend());
  return out;
}

}  // namespace bhnsid::core
