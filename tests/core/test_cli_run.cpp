// bhnsid run end to end with the test plugins: run directory, loop, failure path, introspection.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;
using nlohmann::json;

namespace {
json summary(const std::filesystem::path& run) { return json::parse(read_file(run / "summary.json")); }
}  // namespace

TEST_CASE("core.run.directory_contents", "[core][run]") {
  // A converged run writes params.yaml, log.txt, timers.tsv, scalars.tsv and summary.json with the stable keys.
  TempDir dir;
  const auto parfile = dir.write("case.yaml", counter_parfile("  count: 7\n  scale: 2.0\n"));
  const auto out = dir.path() / "out";
  const ProcessResult r = bhnsid_with_test_plugins({"run", parfile.string(), "--output", out.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const json s = summary(out);
  CHECK(s["status"] == "converged");
  CHECK(s["iterations"] == 3);
  CHECK(s["scalars"]["scale_times_count"] == 14.0);
  for (const char* key : {"version", "git_revision", "build_type", "compiler", "host", "date", "command_line"})
    CHECK(s["provenance"].contains(key));
  CHECK_THAT(s["provenance"]["command_line"].get<std::string>(), Contains("case.yaml"));
  CHECK_THAT(read_file(out / "params.yaml"), Contains("count: 7") && Contains("label: hello") && Contains("max_iterations: 100"));
  CHECK_THAT(read_file(out / "log.txt"), Contains("iteration 3/100") && Contains("status: converged"));
  CHECK_FALSE(std::filesystem::exists(out / "log.txt.partial"));
  CHECK_THAT(read_file(out / "timers.tsv"), Contains("SOLVE\ttp_counter.solve\t3\t") && Contains("TOTAL\ttotal"));
  // The core's own column, the iteration's wall time, comes last.
  CHECK_THAT(read_file(out / "scalars.tsv"),
             Catch::Matches("iteration\tcounter\tseconds\n1\t1\t[0-9.e+-]+\n2\t2\t[0-9.e+-]+\n3\t3\t[0-9.e+-]+\n"));
  CHECK(read_file(out / "order.txt") ==
        "paramcheck\nstartup\nsetup\ninitial\nsolve\nupdate\ncheck\nsolve\nupdate\ncheck\nsolve\nupdate\ncheck\n"
        "analysis\noutput\n");
  CHECK_THAT(read_file(out / "terminate.txt"), Contains("terminate"));
}

TEST_CASE("core.run.default_directory_and_force", "[core][run]") {
  // The default run directory is runs/<stem>; an existing one is refused, --force replaces it.
  TempDir dir;
  dir.write("mycase.yaml", counter_parfile());
  REQUIRE(bhnsid_with_test_plugins({"run", "mycase.yaml"}, dir.path()).exit_code == 0);
  CHECK(std::filesystem::exists(dir.path() / "runs" / "mycase" / "summary.json"));
  const ProcessResult again = bhnsid_with_test_plugins({"run", "mycase.yaml"}, dir.path());
  CHECK(again.exit_code == 2);
  CHECK_THAT(again.err, Contains("exists") && Contains("--force"));
  CHECK(bhnsid_with_test_plugins({"run", "mycase.yaml", "--force"}, dir.path()).exit_code == 0);
}

TEST_CASE("core.run.loop_limit_fails_but_keeps_last_state", "[core][run]") {
  // A loop that never converges stops at run.max_iterations: status failed, exit 1, ANALYSIS
  // skipped, OUTPUT and TERMINATE still run.
  TempDir dir;
  const auto parfile = dir.write("case.yaml", counter_parfile("  converge_after: 0\nrun:\n  max_iterations: 4\n"));
  const auto out = dir.path() / "out";
  const ProcessResult r = bhnsid_with_test_plugins({"run", parfile.string(), "--output", out.string()});
  CHECK(r.exit_code == 1);
  const json s = summary(out);
  CHECK(s["status"] == "failed");
  CHECK(s["iterations"] == 4);
  CHECK_THAT(s["message"].get<std::string>(), Contains("did not converge in run.max_iterations = 4"));
  const std::string order = read_file(out / "order.txt");
  CHECK_THAT(order, !Contains("analysis") && Contains("output"));
  CHECK(std::filesystem::exists(out / "terminate.txt"));
}

TEST_CASE("core.run.failure_in_a_bin", "[core][run]") {
  // A RunFailure in the loop keeps the last state; one before the loop skips OUTPUT; one in
  // OUTPUT still reaches TERMINATE. Each exits 1 with the entry named.
  struct Case {
    const char* bin;
    bool output_written;
  };
  for (const Case c : {Case{"solve", true}, Case{"setup", false}, Case{"output", false}}) {
    TempDir dir;
    const auto parfile = dir.write("case.yaml", counter_parfile(std::string("  fail_in: ") + c.bin + "\n"));
    const auto out = dir.path() / "out";
    const ProcessResult r = bhnsid_with_test_plugins({"run", parfile.string(), "--output", out.string()});
    INFO("fail_in " << c.bin);
    CHECK(r.exit_code == 1);
    const json s = summary(out);
    CHECK(s["status"] == "failed");
    CHECK_THAT(s["message"].get<std::string>(), Contains(std::string("tp_counter.") + c.bin) &&
                                                    Contains(std::string("deliberate failure in ") + c.bin));
    CHECK(std::filesystem::exists(out / "order.txt") == c.output_written);
    CHECK(std::filesystem::exists(out / "terminate.txt"));
  }
}

TEST_CASE("core.run.services_and_ordering_across_plugins", "[core][run]") {
  // A plugin reads another's service and runs where its before/after constraints put it.
  TempDir dir;
  const auto parfile = dir.write("case.yaml", "plugins: [tp_partner, tp_counter]\ntp_counter: {needed: 1}\n");
  const auto out = dir.path() / "out";
  REQUIRE(bhnsid_with_test_plugins({"run", parfile.string(), "--output", out.string()}).exit_code == 0);
  const json s = summary(out);
  CHECK(s["scalars"]["partner_saw_counter"] == 0.0);
  CHECK(s["scalars"]["partner_final_counter"] == 3.0);
  const ProcessResult sched = bhnsid_with_test_plugins({"schedule", parfile.string()});
  CHECK(sched.exit_code == 0);
  const auto first = sched.out.find("tp_partner.before_counter"), second = sched.out.find("tp_counter.initial");
  CHECK(first < second);
  const auto analysis_counter = sched.out.find("tp_counter.analysis"), analysis_partner = sched.out.find("tp_partner.after_counter");
  CHECK(analysis_counter < analysis_partner);
}

TEST_CASE("core.run.params_yaml_round_trips", "[core][run]") {
  // `params --yaml` prints a file that `run` accepts unchanged, and a run's params.yaml reproduces it.
  TempDir dir;
  const ProcessResult tmpl = bhnsid_with_test_plugins({"params", "--yaml", "tp_counter", "tp_partner"});
  REQUIRE(tmpl.exit_code == 0);
  CHECK_THAT(tmpl.out, Contains("REQUIRED") && Contains("needed: 1.5"));
  const auto parfile = dir.write("template.yaml", tmpl.out);
  const auto out1 = dir.path() / "one", out2 = dir.path() / "two";
  REQUIRE(bhnsid_with_test_plugins({"run", parfile.string(), "--output", out1.string(), "--set", "tp_counter.vec=[1, 2.5, 1e-3]"}).exit_code == 0);
  REQUIRE(bhnsid_with_test_plugins({"run", (out1 / "params.yaml").string(), "--output", out2.string()}).exit_code == 0);
  const std::string p1 = read_file(out1 / "params.yaml"), p2 = read_file(out2 / "params.yaml");
  CHECK_THAT(p1, Contains("vec: [1.0, 2.5, 0.001]"));
  CHECK(p1.substr(p1.find("plugins:")) == p2.substr(p2.find("plugins:")));
  CHECK(summary(out1)["scalars"] == summary(out2)["scalars"]);
}

TEST_CASE("core.run.introspection_commands", "[core][run]") {
  // check, params and plugins describe without running; check writes nothing.
  TempDir dir;
  const auto parfile = dir.write("case.yaml", counter_parfile());
  const ProcessResult check = bhnsid_with_test_plugins({"check", parfile.string()}, dir.path());
  CHECK(check.exit_code == 0);
  CHECK_THAT(check.out, Contains("OK"));
  CHECK_FALSE(std::filesystem::exists(dir.path() / "runs"));
  const ProcessResult params = bhnsid_with_test_plugins({"params", "tp_counter"});
  CHECK(params.exit_code == 0);
  CHECK_THAT(params.out, Contains("scale") && Contains("(0, 10]") && Contains("a real in (0, 10]") && Contains("REQUIRED"));
  const ProcessResult plugins = bhnsid_with_test_plugins({"plugins"});
  CHECK_THAT(plugins.out, Contains("tp_counter 1.0") && Contains("implements: counter") &&
                              Contains("tp_bad_abi") && Contains("BROKEN"));
  const ProcessResult unknown = bhnsid_with_test_plugins({"params", "tp_countr"});
  CHECK(unknown.exit_code == 2);
  CHECK_THAT(unknown.err, Contains("did you mean 'tp_counter'"));
}

TEST_CASE("core.run.plugin_path_from_environment", "[core][run]") {
  // BHNSID_PLUGIN_PATH is searched like --plugin-path.
  TempDir dir;
  const auto parfile = dir.write("case.yaml", counter_parfile());
  ::setenv("BHNSID_PLUGIN_PATH", test_plugin_dir().c_str(), 1);
  const ProcessResult r = run_bhnsid({"check", parfile.string()});
  ::unsetenv("BHNSID_PLUGIN_PATH");
  CHECK(r.exit_code == 0);
  CHECK(run_bhnsid({"check", parfile.string()}).exit_code == 2);
}

TEST_CASE("core.run.unknown_command_runs_the_tool_beside_the_executable", "[core][cli]") {
  // git-style: `bhnsid NAME ARGS` runs bhnsid-NAME from the executable's folder, arguments and
  // exit code passed through; a built-in command always wins, and without such a tool the name is
  // an unknown command.
  TempDir dir;
  const auto bin = dir.path() / "bin";
  std::filesystem::create_directories(bin);
  std::filesystem::copy_file(BHNSID_EXE, bin / "bhnsid");
  const auto tool = dir.write("bin/bhnsid-hello", "#!/bin/sh\necho \"hello $*\"\nexit 7\n");
  std::filesystem::permissions(tool, std::filesystem::perms::owner_all);
  dir.write("bin/bhnsid-run", "#!/bin/sh\necho impostor\n");
  std::filesystem::permissions(bin / "bhnsid-run", std::filesystem::perms::owner_all);

  const ProcessResult hello = run_program(bin / "bhnsid", {"hello", "a b", "c"});
  CHECK(hello.exit_code == 7);
  CHECK(hello.out == "hello a b c\n");
  const ProcessResult run = run_program(bin / "bhnsid", {"run", "--help"});
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.out, Contains("--resume"));
  const ProcessResult unknown = run_program(bin / "bhnsid", {"goodbye"});
  CHECK(unknown.exit_code == 2);
  CHECK_THAT(unknown.err, Contains("goodbye"));
}
