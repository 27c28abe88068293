#pragma once
// The checkpoint file (docs/output-format.md, "Checkpoints"): the magic "BHNSIDCK", a format
// version, then records — 'S' a section (a plugin, or the core's "run") and 'E' a named, typed
// entry of that section — and 'Z' with the checksum (Checksum below) of every byte before it. It is
// streamed to checkpoints/checkpoint.NNNNNN.partial and renamed when complete, so a file under its
// final name is whole unless the disk lied; the checksum catches that and any later damage.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "bhnsid/core/checkpoint.hpp"

namespace bhnsid::core {

inline constexpr std::uint32_t checkpoint_format_version = 1;

/// FNV-1a 64 of `bytes` continuing from `hash` (start with fnv_offset), byte by byte: for the
/// build id's files.
inline constexpr std::uint64_t fnv_offset = 14695981039346656037ull;
std::uint64_t fnv1a(std::uint64_t hash, const void* bytes, std::size_t n);

/// The checkpoint's checksum: FNV-1a's step h = (h xor w) * prime on 64-bit little-endian words
/// of the stream (the last, partial word zero-padded, then the byte count), 8 bytes a multiply
/// where the byte-wise hash needs 8: a checkpoint of 500 MB is hashed in a fraction of a second.
/// Every step is a bijection of h, so a change of any one word is always detected.
class Checksum {
 public:
  void add(const void* bytes, std::size_t n);
  std::uint64_t value() const;

 private:
  void word(std::uint64_t w) { hash_ = (hash_ ^ w) * 1099511628211ull; }
  std::uint64_t hash_ = fnv_offset, count_ = 0;
  unsigned char tail_[8] = {};
  std::size_t tail_size_ = 0;
};

class CheckpointFileWriter final : public CheckpointWriter {
 public:
  /// Creates `partial` (truncating a leftover of a killed write).
  explicit CheckpointFileWriter(std::filesystem::path partial);
  ~CheckpointFileWriter() override;
  CheckpointFileWriter(const CheckpointFileWriter&) = delete;
  CheckpointFileWriter& operator=(const CheckpointFileWriter&) = delete;
  /// Starts the entries of `name` (one section per plugin).
  void section(const std::string& name);
  /// Writes the checksum, fsyncs, closes and renames the file to `final_path`.
  void finish(const std::filesystem::path& final_path);

 private:
  void record(const std::string& name, char type, const void* data, std::size_t bytes) override;
  void write(const void* data, std::size_t bytes);
  std::filesystem::path partial_;
  std::FILE* file_ = nullptr;
  Checksum hash_;
  bool in_section_ = false;
};

class CheckpointFileReader final : public CheckpointReader {
 public:
  /// Reads the index of `path` and verifies its checksum; InputError naming the file when it is not
  /// a checkpoint, of another format version, truncated or damaged.
  explicit CheckpointFileReader(std::filesystem::path path);
  ~CheckpointFileReader() override;
  CheckpointFileReader(const CheckpointFileReader&) = delete;
  CheckpointFileReader& operator=(const CheckpointFileReader&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// The accessors read the entries of this section from now on.
  void section(const std::string& name);
  bool has_section(const std::string& name) const { return index_.count(name) > 0; }
  std::vector<std::string> sections() const;
  bool has(const std::string& name) const override;

 private:
  struct Entry {
    char type = 0;
    std::uint64_t offset = 0, bytes = 0;
  };
  const Entry& entry(const std::string& name, char type) const;
  std::size_t size(const std::string& name, char type) const override;
  void read(const std::string& name, char type, void* out, std::size_t bytes) const override;
  std::filesystem::path path_;
  int fd_ = -1;
  std::map<std::string, std::map<std::string, Entry>> index_;
  std::string section_;
};

/// checkpoints/checkpoint.NNNNNN of `iteration`, and the iterations of the complete checkpoints in
/// `dir`, newest first (names alone; the contents are checked when read).
std::filesystem::path checkpoint_path(const std::filesystem::path& dir, int iteration);
std::vector<int> checkpoint_iterations(const std::filesystem::path& dir);
/// A name the program gives an entry of the checkpoint folder: checkpoint.NNNNNN, and its
/// .partial while being written. --force removes these and nothing else of the folder.
bool is_checkpoint_entry_name(const std::string& name);

}  // namespace bhnsid::core
