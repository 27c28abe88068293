#pragma once
// Entries of a run directory are the program's own: a file it writes there is created afresh, never
// opened through what is already at that name, and what it reads there must be the regular file or
// folder it wrote. The threat is a careless user or a shared folder (a symbolic link left pointing
// at a thesis, a FIFO made by a script), not an attacker racing a check against its use: the checks
// are lstat/fstat before the use, and O_NOFOLLOW/O_EXCL where the system offers them.
#include <filesystem>
#include <string>

namespace bhnsid::core {

/// What an existing entry of a run directory must be.
enum class EntryKind { regular_file, folder };

/// True when `path` exists (lstat); InputError naming it when it is not of `kind` (a symbolic link,
/// a FIFO, a device, a file where a folder belongs): the program never writes through, reads from or
/// deletes inside such an entry.
bool require_own_entry(const std::filesystem::path& path, EntryKind kind);

/// Creates `path` for writing as a new file (O_CREAT | O_EXCL | O_NOFOLLOW), after removing a regular
/// file of ours left there by a killed run; anything else at that name is refused (InputError).
/// Returns the open descriptor.
int create_fresh_file(const std::filesystem::path& path);

/// Opens an existing file of ours to append to it (a resumed run's log): a regular file with no
/// other name (a hard link would carry the appended lines into the user's file); InputError otherwise.
int open_own_file_for_appending(const std::filesystem::path& path);

/// Opens an existing regular file of a run directory for reading without following a symbolic link
/// and without waiting on a FIFO (O_NONBLOCK, then fstat); InputError naming it otherwise. `what`
/// names the file's role in the message ("the checkpoint").
int open_own_file_for_reading(const std::filesystem::path& path, const std::string& what);

}  // namespace bhnsid::core
