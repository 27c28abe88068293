// Every bad-input case of the core gives one clear error line, exit code 2, no crash and no run
// directory.
#include <catch2/catch.hpp>
#include <unistd.h>

#include "bhnsid/core/plugin.hpp"
#include "cli_fixture.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;

namespace {
// Runs `bhnsid run` on `yaml` (plus extra args) and checks the common promises of bad input.
std::string expect_bad_input(const std::string& yaml, std::vector<std::string> extra = {}) {
  TempDir dir;
  const auto parfile = dir.write("case.yaml", yaml);
  std::vector<std::string> args{"run", parfile.string(), "--output", (dir.path() / "out").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const ProcessResult r = bhnsid_with_test_plugins(args);
  INFO("stderr: " << r.err);
  CHECK(r.signal == 0);
  CHECK(r.exit_code == 2);
  CHECK(line_count(r.err) == 1);
  CHECK_THAT(r.err, Contains("bhnsid: error: "));
  CHECK_FALSE(std::filesystem::exists(dir.path() / "out"));
  return r.err;
}
}  // namespace

TEST_CASE("core.cli.bad_yaml", "[core][cli]") {
  // Syntax errors, duplicates, deep nesting and empty files name the file (and line:col where there is one).
  CHECK_THAT(expect_bad_input("plugins: [tp_counter\n"), Contains("case.yaml:") && Contains("YAML syntax error"));
  CHECK_THAT(expect_bad_input(counter_parfile("  needed: 3.0\n")), Contains("case.yaml:4:3") && Contains("duplicate key 'needed'"));
  CHECK_THAT(expect_bad_input("plugins: " + std::string(10000, '[') + std::string(10000, ']') + "\n"),
             Contains("nesting deeper"));
  CHECK_THAT(expect_bad_input(""), Contains("case.yaml") && Contains("empty"));
  CHECK_THAT(expect_bad_input("plugins: [tp_counter]\ntp_counter: {needed: 1, label: " + std::string(5u << 20, 'a') + "}\n"),
             Contains("too large"));
}

TEST_CASE("core.cli.missing_or_unreadable_file", "[core][cli]") {
  // A parameter file that does not exist or is a directory is one error naming it.
  TempDir dir;
  for (const auto& path : {dir.path() / "nope.yaml", dir.path()}) {
    const ProcessResult r = bhnsid_with_test_plugins({"check", path.string()});
    CHECK(r.exit_code == 2);
    CHECK(line_count(r.err) == 1);
    CHECK_THAT(r.err, Contains(path.string()));
  }
  if (geteuid() != 0) {  // root reads anything, so unreadability can only be tested as a user
    const auto locked = dir.write("locked.yaml", counter_parfile());
    std::filesystem::permissions(locked, std::filesystem::perms::none);
    const ProcessResult r = bhnsid_with_test_plugins({"check", locked.string()});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains("cannot be read"));
  }
}

TEST_CASE("core.cli.plugins_list_errors", "[core][cli]") {
  // plugins: missing or naming an unknown plugin (with the nearest name).
  CHECK_THAT(expect_bad_input("tp_counter: {needed: 1}\n"), Contains("no 'plugins:' list"));
  CHECK_THAT(expect_bad_input("plugins: [tp_countr]\n"),
             Contains("case.yaml:1:11") && Contains("unknown plugin 'tp_countr'") && Contains("did you mean 'tp_counter'"));
}

TEST_CASE("core.cli.section_and_key_errors", "[core][cli]") {
  // Unknown section or key (nearest name), and a section of an inactive plugin.
  CHECK_THAT(expect_bad_input(counter_parfile("tp_countre: {}\n")),
             Contains("case.yaml:4:1") && Contains("unknown section 'tp_countre'") && Contains("did you mean 'tp_counter'"));
  CHECK_THAT(expect_bad_input(counter_parfile("  scael: 1.0\n")),
             Contains("case.yaml:4:3") && Contains("tp_counter.scael") && Contains("did you mean 'scale'"));
  CHECK_THAT(expect_bad_input(counter_parfile("tp_partner: {}\n")), Contains("not in the plugins: list"));
}

TEST_CASE("core.cli.value_errors", "[core][cli]") {
  // Wrong type, out of range, keyword not in list, NaN/inf, missing required value.
  CHECK_THAT(expect_bad_input(counter_parfile("  count: many\n")),
             Contains("case.yaml:4:10") && Contains("tp_counter.count") && Contains("expected an integer") && Contains("'many'"));
  CHECK_THAT(expect_bad_input(counter_parfile("  scale: 11\n")), Contains("tp_counter.scale") && Contains("(0, 10]"));
  CHECK_THAT(expect_bad_input(counter_parfile("  mode: gama\n")),
             Contains("one of alpha|beta|gamma") && Contains("did you mean 'gamma'"));
  CHECK_THAT(expect_bad_input(counter_parfile("  scale: .nan\n")), Contains("finite real"));
  CHECK_THAT(expect_bad_input(counter_parfile("  vec: [1, .inf, 2]\n")), Contains("finite real"));
  CHECK_THAT(expect_bad_input(counter_parfile("  flag: maybe\n")), Contains("true or false"));
  CHECK_THAT(expect_bad_input("plugins: [tp_counter]\n"), Contains("tp_counter.needed is required"));
}

TEST_CASE("core.cli.set_errors", "[core][cli]") {
  // A --set that does not parse or names an unknown key.
  CHECK_THAT(expect_bad_input(counter_parfile(), {"--set", "tp_counter.scale"}), Contains("expected section.key=value"));
  CHECK_THAT(expect_bad_input(counter_parfile(), {"--set", "tp_counter.scale=[1,"}), Contains("YAML syntax error"));
  CHECK_THAT(expect_bad_input(counter_parfile(), {"--set", "tp_counter.scal=1"}), Contains("did you mean 'scale'"));
  CHECK_THAT(expect_bad_input(counter_parfile(), {"--set", "tp_counter.count=abc"}), Contains("expected an integer"));
  CHECK_THAT(expect_bad_input(counter_parfile(), {"--set", "nosuch.key=1"}), Contains("unknown section 'nosuch'"));
}

TEST_CASE("core.cli.capability_and_schedule_errors", "[core][cli]") {
  // Two providers of one capability, an unmet requirement, a cycle, a dangling reference.
  CHECK_THAT(expect_bad_input("plugins: [tp_counter, tp_twin]\ntp_counter: {needed: 1}\n"),
             Contains("both implement capability 'counter'"));
  CHECK_THAT(expect_bad_input("plugins: [tp_partner]\n"),
             Contains("requires capability 'counter'") && Contains("add one of: tp_counter"));
  CHECK_THAT(expect_bad_input("plugins: [tp_cycle]\n"), Contains("form a cycle"));
  CHECK_THAT(expect_bad_input("plugins: [tp_counter, tp_bad_ref]\ntp_counter: {needed: 1}\n"),
             Contains("tp_bad_ref.late") && Contains("'counter.no_such_entry'") && Contains("tp_counter, which implements 'counter', has no entry 'no_such_entry'"));
  CHECK_THAT(expect_bad_input("plugins: [tp_bad_ref]\n"),
             Contains("tp_bad_ref.late") && Contains("'counter.no_such_entry'") && Contains("no active plugin implements 'counter'"));
}

TEST_CASE("core.cli.broken_plugin_files", "[core][cli]") {
  // Not a shared library, no entry point, another ABI version, a malformed declaration.
  CHECK_THAT(expect_bad_input("plugins: [tp_not_a_library]\n"), Contains("cannot be loaded as a plugin"));
  CHECK_THAT(expect_bad_input("plugins: [tp_no_entry]\n"), Contains("does not export the entry point"));
  CHECK_THAT(expect_bad_input("plugins: [tp_bad_abi]\n"), Contains("ABI version 999") && Contains("ABI version " + std::to_string(BHNSID_ABI_VERSION)));
  CHECK_THAT(expect_bad_input("plugins: [tp_bad_decl]\n"), Contains("without a doc"));
}

TEST_CASE("core.cli.unwritable_output", "[core][cli]") {
  // An output directory that cannot be created or written is one error, exit 2.
  TempDir dir;
  const auto parfile = dir.write("case.yaml", counter_parfile());
  const auto blocker = dir.write("a_file", "x");
  ProcessResult r = bhnsid_with_test_plugins({"run", parfile.string(), "--output", (blocker / "run").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("cannot create the run directory"));
  // /proc refuses new directories even to root, unlike permission bits.
  r = bhnsid_with_test_plugins({"run", parfile.string(), "--output", "/proc/bhnsid-test-run"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("/proc/bhnsid-test-run"));
}

TEST_CASE("core.cli.disk_full", "[core][cli]") {
  // With a file-size limit standing in for a full disk, the run stops with a clear error and
  // leaves no corrupt file under a final name.
  TempDir dir;
  const auto parfile = dir.write("case.yaml", counter_parfile());
  const auto out = dir.path() / "out";
  const ProcessResult r = bhnsid_with_test_plugins({"run", parfile.string(), "--output", out.string()}, {}, 300);
  INFO("stderr: " << r.err);
  CHECK(r.signal == 0);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("cannot write") || Contains("log failed"));
  CHECK_FALSE(std::filesystem::exists(out / "summary.json"));
}

TEST_CASE("core.cli.usage_errors", "[core][cli]") {
  // Unknown subcommands and options are exit 2; --help and --version are exit 0.
  CHECK(run_bhnsid({"frobnicate"}).exit_code == 2);
  CHECK(run_bhnsid({"run"}).exit_code == 2);
  CHECK(run_bhnsid({"run", "x.yaml", "--bogus"}).exit_code == 2);
  const ProcessResult help = run_bhnsid({"run", "--help"});
  CHECK(help.exit_code == 0);
  CHECK_THAT(help.out, Contains("--set") && Contains("--output") && Contains("--force"));
  const ProcessResult version = run_bhnsid({"--version"});
  CHECK(version.exit_code == 0);
  CHECK_THAT(version.out, Contains("bhnsid 0."));
}
