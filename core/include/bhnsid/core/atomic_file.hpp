#pragma once
// Crash-safe output: a file appears under its final name only when it is complete.
#include <filesystem>
#include <string>

namespace bhnsid::core {

/// Writes `contents` to a temporary file beside `path`, fsyncs it, renames it over `path` and
/// fsyncs the directory. Any failure (disk full, read-only, ...) removes the temporary and throws
/// InputError naming the file and the system's reason; `path` is then untouched.
void write_file_atomic(const std::filesystem::path& path, const std::string& contents);

/// Renames a finished file into place and fsyncs both; InputError on failure.
void commit_file(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace bhnsid::core
