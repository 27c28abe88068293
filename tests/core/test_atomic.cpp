// Atomic writes: a file appears whole or not at all, and the old version survives a failure.
#include <catch2/catch.hpp>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include "bhnsid/core/atomic_file.hpp"
#include "bhnsid/core/errors.hpp"
#include "process.hpp"

using namespace bhnsid::core;
using bhnsid::test::TempDir;
using bhnsid::test::read_file;
using Catch::Matchers::Contains;

TEST_CASE("core.atomic.replace_and_no_temporaries_left", "[core][atomic]") {
  // A rewrite replaces the content and leaves no temporary file behind.
  TempDir dir;
  const auto file = dir.path() / "summary.json";
  write_file_atomic(file, "first");
  write_file_atomic(file, "second");
  CHECK(read_file(file) == "second");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++entries;
  CHECK(entries == 1);
}

TEST_CASE("core.atomic.failed_write_keeps_old_file", "[core][atomic]") {
  // With the disk "full" (a file-size limit), the write fails cleanly and the old file is intact.
  TempDir dir;
  const auto file = dir.path() / "result.tsv";
  write_file_atomic(file, "old contents\n");
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit{100, 100};
    setrlimit(RLIMIT_FSIZE, &limit);
    try {
      write_file_atomic(file, std::string(100000, 'x'));
    } catch (const InputError&) {
      _exit(42);
    }
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 42);
  CHECK(read_file(file) == "old contents\n");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++entries;
  CHECK(entries == 1);
}
