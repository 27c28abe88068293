// The entries of a run directory are the program's own: a symbolic link, FIFO or user's file left
// at one of their names is refused (exit 2, naming it), never written through, read from as if it
// were ours, or deleted; --force removes the checkpoints it wrote and nothing else of their folder.
#include <catch2/catch.hpp>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const char* const parfile_text =
    "plugins: [tp_checkpoint, tp_output]\nrun:\n  max_iterations: 60\n  checkpoint_overhead: 1.0e9\n";

ProcessResult run(const fs::path& parfile, const fs::path& out, std::vector<std::string> extra = {}) {
  return run_parfile_with_test_plugins(parfile, out, std::move(extra));
}

// A run stopped by run.max_iterations (exit 1) with its checkpoints, and a user's file beside it.
struct Stopped {
  TempDir dir;
  fs::path parfile, out, victim;
  Stopped()
      : parfile(dir.write("case.yaml", parfile_text)), out(dir.path() / "stopped"),
        victim(dir.write("thesis.tex", "my thesis\n")) {
    const ProcessResult r = run(parfile, out, {"--set", "run.max_iterations=8"});
    INFO(r.err);
    REQUIRE(r.exit_code == 1);
    REQUIRE(fs::exists(out / "checkpoints" / "checkpoint.000008"));
  }
  ProcessResult resume() { return run(parfile, out, {"--resume"}); }
};

void expect_refused(const ProcessResult& r, const std::string& entry) {
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 2);
  CHECK(line_count(r.err) == 1);
  CHECK_THAT(r.err, Contains(entry) && Contains("symbolic link"));
}

}  // namespace

TEST_CASE("core.owned_entries.resume_never_writes_through_a_link", "[core][hostile][resume]") {
  // --resume appended its log to the link's target, and HDF5-style outputs truncated theirs.
  SECTION("log.txt.partial") {
    Stopped s;
    fs::create_symlink(s.victim, s.out / "log.txt.partial");
    expect_refused(s.resume(), "log.txt.partial");
    CHECK(read_file(s.victim) == "my thesis\n");
  }
  SECTION("an output written by path (data.h5.partial)") {
    Stopped s;
    fs::create_symlink(s.victim, s.out / "blob.bin.partial");
    const ProcessResult r = run(s.parfile, s.out, {"--resume", "--set", "run.max_iterations=60"});
    INFO("stderr: " << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("blob.bin.partial") && Contains("symbolic link"));
    CHECK(read_file(s.victim) == "my thesis\n");
    CHECK(fs::is_symlink(s.out / "blob.bin.partial"));
  }
  SECTION("params.yaml, read back by the resume") {
    Stopped s;
    fs::remove(s.out / "params.yaml");
    fs::create_symlink(s.victim, s.out / "params.yaml");
    expect_refused(s.resume(), "params.yaml");
    CHECK(read_file(s.victim) == "my thesis\n");
  }
}

TEST_CASE("core.owned_entries.a_linked_checkpoint_folder_is_refused", "[core][hostile][resume]") {
  // The checkpoint rotation after each resumed iteration deleted the linked folder's files.
  Stopped s;
  const fs::path elsewhere = s.dir.path() / "my_checkpoints";
  fs::rename(s.out / "checkpoints", elsewhere);
  fs::create_symlink(elsewhere, s.out / "checkpoints");
  const auto before = std::distance(fs::directory_iterator(elsewhere), fs::directory_iterator());
  const ProcessResult r = run(s.parfile, s.out, {"--resume", "--set", "run.max_iterations=60"});
  expect_refused(r, "checkpoints");
  CHECK(std::distance(fs::directory_iterator(elsewhere), fs::directory_iterator()) == before);
  // A warm start reads through no link either.
  const ProcessResult warm = run(s.parfile, s.dir.path() / "warm", {"--warm-start", s.out.string()});
  expect_refused(warm, "checkpoints");
  CHECK_FALSE(fs::exists(s.dir.path() / "warm"));
}

TEST_CASE("core.owned_entries.a_fifo_checkpoint_is_not_waited_on", "[core][hostile][resume]") {
  // A FIFO as the newest checkpoint blocked --resume and --warm-start until killed.
  Stopped s;
  REQUIRE(::mkfifo((s.out / "checkpoints" / "checkpoint.000099").c_str(), 0644) == 0);
  const auto t0 = std::chrono::steady_clock::now();
  const ProcessResult warm = run(s.parfile, s.dir.path() / "warm", {"--warm-start", s.out.string()});
  INFO("stderr: " << warm.err);
  CHECK(warm.exit_code == 2);
  CHECK_THAT(warm.err, Contains("checkpoint.000099") && Contains("FIFO"));
  // --resume skips it, as it skips any checkpoint that does not read back, and says so.
  const ProcessResult resumed = run(s.parfile, s.out, {"--resume", "--set", "run.max_iterations=60"});
  INFO("stderr: " << resumed.err);
  CHECK(resumed.exit_code == 0);
  CHECK_THAT(resumed.err, Contains("checkpoint.000099") && Contains("FIFO"));
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 20);
}

TEST_CASE("core.owned_entries.force_keeps_what_the_user_put_in_the_checkpoint_folder", "[core][hostile]") {
  // --force removed the recorded checkpoints/ folder whole, a user's notes in it included.
  Stopped s;
  const auto notes = s.dir.write("stopped/checkpoints/my_notes.txt", "why iteration 8\n");
  const ProcessResult r = run(s.parfile, s.out, {"--force"});
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 2);
  CHECK(line_count(r.err) == 1);
  CHECK_THAT(r.err, Contains("checkpoints/my_notes.txt"));
  CHECK(read_file(notes) == "why iteration 8\n");
  CHECK(fs::exists(s.out / "checkpoints" / "checkpoint.000008"));
  // Without the notes, --force replaces the run, its checkpoints included.
  fs::remove(notes);
  const ProcessResult again = run(s.parfile, s.out, {"--force"});
  INFO("stderr: " << again.err);
  CHECK(again.exit_code == 0);
  CHECK_FALSE(fs::exists(s.out / "checkpoints" / "checkpoint.000008"));
}

TEST_CASE("core.owned_entries.a_resume_names_what_differs", "[core][resume]") {
  // Another plugin set was reported as "another build of bhnsid"; following the warning
  // "set run.threads = N" was refused.
  Stopped s;
  const auto other = s.dir.write("other.yaml", "plugins: [tp_checkpoint]\nrun:\n  max_iterations: 60\n");
  const ProcessResult plugins = run(other, s.out, {"--resume"});
  INFO("stderr: " << plugins.err);
  CHECK(plugins.exit_code == 2);
  CHECK(line_count(plugins.err) == 1);
  CHECK_THAT(plugins.err, Contains("another plugin set") && Contains("lacks tp_output"));
  CHECK_THAT(plugins.err, !Contains("another build"));
  const ProcessResult warm = run(other, s.dir.path() / "warm", {"--warm-start", s.out.string()});
  INFO("stderr: " << warm.err);
  CHECK(warm.exit_code == 2);
  CHECK_THAT(warm.err, Contains("lacks tp_output") && !Contains("another build"));
  const ProcessResult threads = run(s.parfile, s.out, {"--resume", "--set", "run.threads=1", "--set", "run.max_iterations=60"});
  INFO("stderr: " << threads.err);
  CHECK(threads.exit_code == 0);
}

TEST_CASE("core.owned_entries.two_resumes_of_one_directory_cannot_both_run", "[core][resume]") {
  // The lock a running resume holds (flock on the directory), held here by the test itself.
  Stopped s;
  const int fd = ::open(s.out.c_str(), O_RDONLY | O_DIRECTORY);
  REQUIRE(fd >= 0);
  REQUIRE(::flock(fd, LOCK_EX | LOCK_NB) == 0);
  const std::string log_before = read_file(s.out / "log.txt");
  const ProcessResult r = run(s.parfile, s.out, {"--resume", "--set", "run.max_iterations=60"});
  ::close(fd);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("in use by another bhnsid process"));
  CHECK(read_file(s.out / "log.txt") == log_before);
}

TEST_CASE("core.owned_entries.a_hard_link_or_a_name_like_ours_is_the_users", "[core][hostile][resume]") {
  SECTION("--resume appends to no hard link") {
    Stopped s;
    REQUIRE(::link(s.victim.c_str(), (s.out / "log.txt.partial").c_str()) == 0);
    const ProcessResult r = s.resume();
    INFO("stderr: " << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("log.txt.partial") && Contains("hard link"));
    CHECK(read_file(s.victim) == "my thesis\n");
  }
  SECTION("--force removes no folder or file of the user's that is named like our temporaries") {
    Stopped s;
    fs::create_directories(s.out / "params.yaml.tmp.backup");
    const auto kept = s.dir.write("stopped/params.yaml.tmp.backup/thesis.tex", "chapter 1\n");
    const ProcessResult r = run(s.parfile, s.out, {"--force"});
    INFO("stderr: " << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("params.yaml.tmp.backup"));
    CHECK(read_file(kept) == "chapter 1\n");
  }
  SECTION("a refused resume leaves the marker as it was") {
    Stopped s;
    const std::string marker = read_file(s.out / ".bhnsid-run.json");
    fs::create_symlink(s.victim, s.out / "log.txt.partial");
    CHECK(s.resume().exit_code == 2);
    CHECK(read_file(s.out / ".bhnsid-run.json") == marker);
  }
  SECTION("a link at a final name is refused, not silently replaced") {
    Stopped s;
    fs::remove(s.out / "summary.json");
    fs::create_symlink(s.victim, s.out / "summary.json");
    const ProcessResult r = s.resume();
    INFO("stderr: " << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("summary.json") && Contains("symbolic link"));
    CHECK(fs::is_symlink(s.out / "summary.json"));
    CHECK(read_file(s.victim) == "my thesis\n");
  }
}

TEST_CASE("core.owned_entries.a_name_that_is_not_utf8_is_kept", "[core][hostile]") {
  // A run directory named with the byte 0xff ran, then ended as an internal error (exit 3) when its
  // summary.json, which quotes the command line, was written as JSON.
  Stopped s;
  const fs::path out = s.dir.path() / std::string("r\xff");
  const ProcessResult r = run(s.parfile, out);
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 0);
  CHECK(fs::exists(out / "summary.json"));
  CHECK(fs::exists(out / "log.txt"));
}
