// bhnsid run --resume with the test plugins: tp_checkpoint keeps its loop state in memory only,
// tp_kill dies by SIGKILL where BHNSID_TEST_KILL says. A resumed run must end exactly where an
// uninterrupted one ends; a damaged, foreign or mismatched checkpoint is refused or skipped, and a
// refused resume leaves the earlier run untouched.
#include <catch2/catch.hpp>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_fixture.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Every iteration's checkpoint, however slow the machine (checkpoint_overhead: no time limit).
const char* const parfile_text =
    "plugins: [tp_checkpoint, tp_kill]\nrun:\n  max_iterations: 60\n  checkpoint_overhead: 1.0e9\n";

/// Sets BHNSID_TEST_KILL for the children started while it lives.
struct KillAt {
  explicit KillAt(const std::string& where) { ::setenv("BHNSID_TEST_KILL", where.c_str(), 1); }
  ~KillAt() { ::unsetenv("BHNSID_TEST_KILL"); }
};

ProcessResult run(const fs::path& parfile, const fs::path& out, std::vector<std::string> extra = {}) {
  return run_parfile_with_test_plugins(parfile, out, std::move(extra));
}

std::string fmt_checkpoint(int iteration) {
  char name[32];
  std::snprintf(name, sizeof name, "checkpoint.%06d", iteration);
  return name;
}

json scalars(const fs::path& run_dir) { return json::parse(read_file(run_dir / "summary.json"))["scalars"]; }

// scalars.tsv without the core's wall-time column (the last), which no two runs share.
std::string history(const fs::path& run_dir) {
  std::istringstream in(read_file(run_dir / "scalars.tsv"));
  std::string out;
  for (std::string line; std::getline(in, line);) out += line.substr(0, line.rfind('\t')) + "\n";
  return out;
}

void flip_byte(const fs::path& file, std::uintmax_t at) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(static_cast<std::streamoff>(at));
  char c = 0;
  f.get(c);
  f.seekp(static_cast<std::streamoff>(at));
  f.put(static_cast<char>(c ^ 0x5a));
}

struct Reference {
  TempDir dir;
  fs::path parfile, out;
  Reference() : parfile(dir.write("case.yaml", parfile_text)), out(dir.path() / "reference") {
    const ProcessResult r = run(parfile, out);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
  }
};

void same_result(const Reference& ref, const fs::path& resumed) {
  CHECK(scalars(resumed) == scalars(ref.out));
  CHECK(history(resumed) == history(ref.out));
  CHECK(json::parse(read_file(resumed / "summary.json"))["status"] == "converged");
  CHECK(json::parse(read_file(resumed / "summary.json"))["iterations"] ==
        json::parse(read_file(ref.out / "summary.json"))["iterations"]);
}

}  // namespace

TEST_CASE("core.resume.killed_runs_end_where_an_uninterrupted_run_ends", "[core][run][resume]") {
  Reference ref;
  const int steps = static_cast<int>(scalars(ref.out)["steps"].get<double>());
  REQUIRE(steps > 12);  // the kills below land inside the loop
  for (int k : {2, 7, 12}) {
    DYNAMIC_SECTION("killed at the start of iteration " << k) {
      const fs::path out = ref.dir.path() / ("killed" + std::to_string(k));
      {
        KillAt kill("solve:" + std::to_string(k));
        const ProcessResult r = run(ref.parfile, out);
        REQUIRE(r.signal == SIGKILL);
      }
      CHECK(fs::exists(out / "checkpoints" / fmt_checkpoint(k - 1)));
      CHECK_FALSE(fs::exists(out / "summary.json"));
      const ProcessResult r = run(ref.parfile, out, {"--resume"});
      INFO(r.err);
      REQUIRE(r.exit_code == 0);
      same_result(ref, out);
      const std::string log = read_file(out / "log.txt");
      CHECK_THAT(log, Contains("resumed from") && Contains("iteration " + std::to_string(k - 1) + "/60"));
      CHECK_FALSE(fs::exists(out / "log.txt.partial"));
      // The newest two are kept.
      int kept = 0;
      for (const auto& e : fs::directory_iterator(out / "checkpoints")) kept += e.path().extension() != ".partial";
      CHECK(kept == 2);
    }
  }
}

TEST_CASE("core.resume.a_kill_during_a_checkpoint_write_loses_only_that_checkpoint", "[core][run][resume]") {
  Reference ref;
  const fs::path out = ref.dir.path() / "killed";
  {
    KillAt kill("save:6");
    REQUIRE(run(ref.parfile, out).signal == SIGKILL);
  }
  const fs::path partial = out / "checkpoints" / (fmt_checkpoint(6) + ".partial");
  REQUIRE(fs::exists(partial));
  CHECK(fs::file_size(partial) > 1000000);  // killed in the middle of tp_kill's 4 MiB
  CHECK_FALSE(fs::exists(out / "checkpoints" / fmt_checkpoint(6)));
  const ProcessResult r = run(ref.parfile, out, {"--resume"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.err, Contains("unfinished checkpoint write"));
  CHECK_THAT(read_file(out / "log.txt"), Contains("after iteration 5"));
  CHECK_FALSE(fs::exists(partial));
  same_result(ref, out);
}

TEST_CASE("core.resume.a_damaged_checkpoint_is_skipped_and_none_is_refused", "[core][run][resume]") {
  Reference ref;
  const fs::path out = ref.dir.path() / "stopped";
  // Out of iterations after 8: a failed run, whose checkpoints 7 and 8 a larger limit continues.
  REQUIRE(run(ref.parfile, out, {"--set", "run.max_iterations=8"}).exit_code == 1);
  const fs::path newest = out / "checkpoints" / fmt_checkpoint(8), older = out / "checkpoints" / fmt_checkpoint(7);
  REQUIRE(fs::exists(newest));
  REQUIRE(fs::exists(older));
  flip_byte(newest, fs::file_size(newest) / 2);

  SECTION("the older one is used") {
    const ProcessResult r = run(ref.parfile, out, {"--resume"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.err, Contains(newest.string()) && Contains("checksum"));
    CHECK_THAT(read_file(out / "log.txt"), Contains("after iteration 7"));
    same_result(ref, out);
  }
  SECTION("both damaged: refused, the run left as it was") {
    fs::resize_file(older, fs::file_size(older) - 3);
    const std::string summary_before = read_file(out / "summary.json"), log_before = read_file(out / "log.txt");
    const ProcessResult r = run(ref.parfile, out, {"--resume"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("bhnsid: error:") && Contains("no checkpoint there reads back whole") &&
                          Contains("truncated") && Contains("checksum"));
    CHECK(read_file(out / "summary.json") == summary_before);
    CHECK(read_file(out / "log.txt") == log_before);
    CHECK(fs::exists(newest));
    CHECK(fs::exists(older));
  }
  SECTION("not a checkpoint at all") {
    { std::ofstream(newest, std::ios::trunc) << "a text file, not a checkpoint\n"; }
    fs::remove(older);
    const ProcessResult r = run(ref.parfile, out, {"--resume"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("does not start with BHNSIDCK"));
  }
}

TEST_CASE("core.resume.other_parameters_are_refused_but_more_iterations_are_allowed", "[core][run][resume]") {
  Reference ref;
  const fs::path out = ref.dir.path() / "stopped";
  REQUIRE(run(ref.parfile, out, {"--set", "run.max_iterations=8"}).exit_code == 1);
  const std::string summary_before = read_file(out / "summary.json"), log_before = read_file(out / "log.txt");
  const std::string params_before = read_file(out / "params.yaml");

  const ProcessResult refused = run(ref.parfile, out, {"--resume", "--set", "tp_checkpoint.target=4"});
  CHECK(refused.exit_code == 2);
  CHECK(line_count(refused.err) == 1);
  CHECK_THAT(refused.err, Contains(ref.parfile.string()) && Contains("tp_checkpoint.target") &&
                              Contains("tp_checkpoint.target = 3") && Contains("tp_checkpoint.target = 4"));
  CHECK(read_file(out / "summary.json") == summary_before);
  CHECK(read_file(out / "log.txt") == log_before);

  const ProcessResult more = run(ref.parfile, out, {"--resume", "--set", "run.max_iterations=60"});
  INFO(more.err);
  REQUIRE(more.exit_code == 0);
  same_result(ref, out);
  CHECK(read_file(out / "params.yaml") == params_before);
  // One log: the first run's lines, then the resumed run's.
  const std::string log = read_file(out / "log.txt");
  CHECK(log.rfind(log_before.substr(0, 200), 0) == 0);
  CHECK_THAT(log, Contains("resumed from") && Contains("status: converged"));
}

TEST_CASE("core.resume.another_build_is_refused", "[core][run][resume]") {
  Reference ref;
  const fs::path out = ref.dir.path() / "stopped";
  REQUIRE(run(ref.parfile, out, {"--set", "run.max_iterations=8"}).exit_code == 1);
  // The same plugin with one byte more: another build of it (the loader takes it as it is).
  const fs::path plugins = ref.dir.path() / "plugins";
  fs::create_directories(plugins);
  for (const char* name : {"libbhnsid_tp_checkpoint.so", "libbhnsid_tp_kill.so"})
    fs::copy_file(test_plugin_dir() / name, plugins / name);
  { std::ofstream(plugins / "libbhnsid_tp_checkpoint.so", std::ios::app | std::ios::binary) << '\0'; }
  const ProcessResult r =
      run_bhnsid({"run", ref.parfile.string(), "--output", out.string(), "--resume", "--plugin-path", plugins.string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("written by another build of bhnsid") && Contains(fmt_checkpoint(8)));
  // The unchanged copies are the same build: accepted.
  fs::copy_file(test_plugin_dir() / "libbhnsid_tp_checkpoint.so", plugins / "libbhnsid_tp_checkpoint.so",
                fs::copy_options::overwrite_existing);
  const ProcessResult same =
      run_bhnsid({"run", ref.parfile.string(), "--output", out.string(), "--resume", "--set", "run.max_iterations=60",
                  "--plugin-path", plugins.string()});
  INFO(same.err);
  CHECK(same.exit_code == 0);
}

TEST_CASE("core.resume.needs_a_run_directory_with_a_checkpoint", "[core][run][resume]") {
  TempDir dir;
  const auto parfile = dir.write("case.yaml", parfile_text);
  const ProcessResult missing = run(parfile, dir.path() / "nothing", {"--resume"});
  CHECK(missing.exit_code == 2);
  CHECK_THAT(missing.err, Contains("no run directory to resume"));
  fs::create_directories(dir.path() / "foreign");
  dir.write("foreign/notes.txt", "mine\n");
  const ProcessResult foreign = run(parfile, dir.path() / "foreign", {"--resume"});
  CHECK(foreign.exit_code == 2);
  CHECK_THAT(foreign.err, Contains("not a bhnsid run directory"));
  CHECK(read_file(dir.path() / "foreign" / "notes.txt") == "mine\n");
  const ProcessResult both = run(parfile, dir.path() / "x", {"--resume", "--force"});
  CHECK(both.exit_code == 2);
  CHECK_THAT(both.err, Contains("excludes"));
  // Killed before its first iteration ended: nothing to resume from.
  {
    KillAt kill("solve:1");
    REQUIRE(run(parfile, dir.path() / "early").signal == SIGKILL);
  }
  const ProcessResult early = run(parfile, dir.path() / "early", {"--resume"});
  CHECK(early.exit_code == 2);
  CHECK_THAT(early.err, Contains("no checkpoint to resume from"));
  // checkpoint_every = 0 writes none.
  REQUIRE(run(parfile, dir.path() / "none", {"--set", "run.checkpoint_every=0"}).exit_code == 0);
  CHECK_FALSE(fs::exists(dir.path() / "none" / "checkpoints"));
}

TEST_CASE("core.resume.a_converged_run_resumes_straight_to_its_output", "[core][run][resume]") {
  Reference ref;
  const std::string before = history(ref.out);
  const ProcessResult r = run(ref.parfile, ref.out, {"--resume"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(read_file(ref.out / "log.txt"), Contains("straight to ANALYSIS"));
  CHECK(history(ref.out) == before);
  CHECK(scalars(ref.out)["steps"].get<double>() > 12);
}

TEST_CASE("core.resume.checkpoints_wait_while_the_last_one_cost_too_much", "[core][run][resume]") {
  // With a budget of 1e-9 of the time since, only the first checkpoint (nothing to wait for) and
  // the converged one (always) are written.
  TempDir dir;
  const auto parfile = dir.write("case.yaml", parfile_text);
  const fs::path out = dir.path() / "out";
  REQUIRE(run(parfile, out, {"--set", "run.checkpoint_overhead=1e-9"}).exit_code == 0);
  const int steps = static_cast<int>(scalars(out)["steps"].get<double>());
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(out / "checkpoints")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{fmt_checkpoint(1), fmt_checkpoint(steps)});
  CHECK_THAT(read_file(out / "log.txt"), Contains("iteration 1: checkpoint written in"));
}

TEST_CASE("core.resume.a_stop_during_the_restore_is_a_stop", "[core][run][resume]") {
  // A converged checkpoint goes straight to ANALYSIS, where no signal is polled: a SIGINT that
  // arrived while the checkpoint was restored used to end as "converged", exit 0.
  Reference ref;
  const std::string data_before = read_file(ref.out / "scalars.tsv");
  KillAt signal_at("sigint_in_restore");
  const ProcessResult r = run(ref.parfile, ref.out, {"--resume"});
  INFO(r.err);
  CHECK(r.exit_code == 130);
  CHECK(json::parse(read_file(ref.out / "summary.json"))["status"] == "interrupted");
  CHECK(read_file(ref.out / "scalars.tsv") == data_before);
}
