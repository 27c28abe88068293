// The run directory: recognised by its marker, locked while in use, and --force replaces only
// what the program wrote (issue 19: --force used to delete any folder holding a params.yaml).
#include <catch2/catch.hpp>
#include <unistd.h>

#include <filesystem>

#include "bhnsid/core/atomic_file.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/run_directory.hpp"
#include "process.hpp"

using namespace bhnsid::core;
using bhnsid::test::read_file;
using bhnsid::test::TempDir;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {
void write_recorded(RunDirectory& dir, const std::string& name, const std::string& text) {
  dir.record(name);
  write_file_atomic(dir.path() / name, text);
}
}  // namespace

TEST_CASE("core.run_directory.marker_and_force", "[core][run_directory]") {
  // A new directory carries the marker listing what was written; without force an existing one is
  // refused; with force (once unlocked) the recorded files are replaced.
  TempDir tmp;
  const fs::path run = tmp.path() / "a" / "run";
  {
    RunDirectory dir(run, false, "run", {});
    write_recorded(dir, "summary.json", "{}");
    CHECK_THAT(read_file(run / run_marker_name), Contains("\"summary.json\"") && Contains("bhnsid run directory"));
  }
  CHECK_THROWS_WITH(RunDirectory(run, false, "run", {}), Contains("exists") && Contains("--force"));
  RunDirectory again(run, true, "run", {});
  CHECK_FALSE(fs::exists(run / "summary.json"));
  CHECK(fs::exists(run / run_marker_name));
}

TEST_CASE("core.run_directory.force_never_deletes_foreign_files", "[core][run_directory]") {
  // A folder with params.yaml, thesis.tex and chapters/ (no marker) loses nothing; a real run
  // directory to which the user added a file is refused too, naming the file.
  TempDir tmp;
  const fs::path precious = tmp.path() / "precious";
  fs::create_directories(precious / "chapters");
  write_file_atomic(precious / "params.yaml", "plugins: [x]\n");
  write_file_atomic(precious / "thesis.tex", "years of work");
  CHECK_THROWS_WITH(RunDirectory(precious, true, "run", {}),
                    Contains("not a bhnsid run directory") && Contains("thesis.tex") && Contains("chapters"));
  CHECK(read_file(precious / "thesis.tex") == "years of work");
  CHECK(fs::exists(precious / "params.yaml"));
  CHECK(fs::is_directory(precious / "chapters"));

  const fs::path run = tmp.path() / "run";
  { RunDirectory dir(run, false, "run", {}); write_recorded(dir, "log.txt", "x"); }
  write_file_atomic(run / "notes.md", "mine");
  CHECK_THROWS_WITH(RunDirectory(run, true, "run", {}), Contains("notes.md") && !Contains("log.txt,"));
  CHECK(read_file(run / "notes.md") == "mine");
  CHECK(read_file(run / "log.txt") == "x");
  // A marker of another format is not ours.
  write_file_atomic(run / run_marker_name, "{\"format\": \"something else\"}");
  fs::remove(run / "notes.md");
  CHECK_THROWS_WITH(RunDirectory(run, true, "run", {}), Contains("not a marker this program wrote"));
  CHECK(fs::exists(run / "log.txt"));
}

TEST_CASE("core.run_directory.locked_while_in_use", "[core][run_directory]") {
  // A directory held by a live run is refused at once, even with force, naming the PID.
  TempDir tmp;
  const fs::path run = tmp.path() / "run";
  RunDirectory live(run, false, "run", {});
  write_recorded(live, "log.txt.partial", "running");
  CHECK_THROWS_WITH(RunDirectory(run, true, "run", {}), Contains("in use") && Contains(std::to_string(::getpid())));
  CHECK(read_file(run / "log.txt.partial") == "running");
}

TEST_CASE("core.run_directory.protected_folders_and_abandon", "[core][run_directory]") {
  // The parameter file's folder is never replaced; abandon() removes what this object made.
  TempDir tmp;
  const fs::path run = tmp.path() / "run";
  { RunDirectory dir(run, false, "run", {}); write_recorded(dir, "params.yaml", "x"); }
  CHECK_THROWS_WITH(RunDirectory(run, true, "run", {run / "params.yaml"}), Contains("parameter file"));
  CHECK(fs::exists(run / "params.yaml"));
  const fs::path fresh = tmp.path() / "fresh";
  RunDirectory dir(fresh, false, "run", {});
  write_recorded(dir, "summary.json", "{}");
  dir.abandon();
  CHECK_FALSE(fs::exists(fresh));
  CHECK_THROWS_WITH(RunDirectory("", false, "run", {}), Contains("empty"));
}
