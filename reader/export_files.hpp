#pragma once
// bhnsid-export's own files: the points file, read only when it is a regular file of bounded size,
// and the output table, written under a fresh private name in its folder and renamed into place.
// The threat is a careless user or a shared folder (a symbolic link or a FIFO left at a name, a
// file of the same name kept there), not an attacker racing a check against its use.
#include <cstddef>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace bhnsid::exporter {

/// Bad input: one line for stderr, exit 2.
struct BadInput {
  std::string message;
};

/// What a points file may hold: enough for any table a person reads; an evolution code with more
/// points links the library.
constexpr std::size_t max_points_file_bytes = std::size_t(256) << 20;
constexpr std::size_t max_points_line = 4096;
constexpr std::size_t max_points = 10000000;

struct Points {
  std::vector<double> x, y, z;
};

/// The points of `path` (x y z a line, '#' comments); BadInput naming the file and line otherwise.
Points read_points(const std::string& path);

/// Refuses (BadInput) what --output may not name, before any work is done: an existing entry
/// without --force; with --force anything but a regular file, or the data or points file itself.
void check_output(const std::string& output, bool force, const std::vector<std::string>& inputs);

/// Writes the table through `write` into a new private file in the output's folder (O_EXCL), fsyncs
/// it and renames it to `output` (without --force, a link that fails if the name appeared
/// meanwhile); the temporary is removed on any failure and on SIGINT/SIGTERM/SIGHUP.
void write_output(const std::string& output, bool force, const std::function<void(std::FILE*)>& write);

/// `text` with control characters and bytes that are not UTF-8 as \xNN: a message stays one line.
std::string printable(const std::string& text);

}  // namespace bhnsid::exporter
