#pragma once
// A directory the program writes a run (or a validate series) into, recognisable beyond doubt by a
// marker file of its own format, .bhnsid-run.json, which lists every file the program wrote there.
// The directory is locked (flock, exclusive) for as long as the object lives, so a second run into
// it is refused at once, naming the PID that holds it. --force replaces only what the marker lists,
// and refuses a directory holding anything else, a locked one, the parameter file's own folder,
// the working directory and its parents.
#include <filesystem>
#include <string>
#include <vector>

namespace bhnsid::core {

inline constexpr const char* run_marker_name = ".bhnsid-run.json";

class RunDirectory {
 public:
  /// Creates `dir` (its parents too) or, with `force`, takes over an existing one that a previous
  /// run of this program wrote, removing what that run wrote. `kind` ("run", "validate") is recorded
  /// in the marker. A directory holding one of `protect` (the parameter file) is never replaced. Throws
  /// InputError naming the directory and the reason; on failure nothing is left that was not there.
  RunDirectory(std::filesystem::path dir, bool force, std::string kind, const std::vector<std::filesystem::path>& protect);
  /// Reopens the directory of an earlier run of `kind` to continue it (bhnsid run --resume):
  /// locks it and keeps everything in it, its marker included until take_over(); abandon() then
  /// removes nothing.
  struct ReopenTag {};
  RunDirectory(std::filesystem::path dir, std::string kind, ReopenTag);
  ~RunDirectory();
  RunDirectory(const RunDirectory&) = delete;
  RunDirectory& operator=(const RunDirectory&) = delete;

  const std::filesystem::path& path() const { return dir_; }
  /// Marks a reopened directory as this process's (its PID in the marker), once the resume is
  /// known to go ahead: a refused one leaves the marker as it was.
  void take_over();
  /// Records, before it is written, that the program writes `name` (a file or sub-directory
  /// directly inside), so that a later --force may replace it.
  void record(const std::string& name);
  /// Records the checkpoint folder, so that a later --force removes the entries the program names
  /// there (checkpoint.NNNNNN) and then the folder; anything else inside, or a symbolic link in
  /// its place, makes --force refuse, naming it.
  void record_folder(const std::string& name);
  /// Removes what was recorded, the marker and, when this object created them, the directory and
  /// the folders above it (when empty): used when a run fails before anything has run.
  void abandon();

 private:
  void lock();
  void write_marker();
  void remove_created_parents();
  std::filesystem::path dir_;
  std::string kind_;
  std::string started_;
  int fd_ = -1;
  bool created_ = false;
  bool reopened_ = false;
  std::filesystem::path first_created_parent_;  ///< the topmost folder above dir_ this object created
  std::vector<std::string> files_;
  std::vector<std::string> folders_;
};

}  // namespace bhnsid::core
