// The core's retreat after a SOLVE step failure (a diverging field solve): RETREAT, then UPDATE again
// with half the step, then SOLVE, at most run.max_retreats times; never at the first iteration.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;
using nlohmann::json;

namespace {

struct Outcome {
  ProcessResult process;
  json summary;
  std::string steps;
};

Outcome run_case(const std::string& section) {
  TempDir dir;
  const auto parfile = dir.write("case.yaml", "plugins: [tp_step_failure]\n" + section);
  const auto out = dir.path() / "out";
  Outcome o;
  o.process = bhnsid_with_test_plugins({"run", parfile.string(), "--output", out.string()});
  o.summary = json::parse(read_file(out / "summary.json"));
  o.steps = read_file(out / "steps.txt");
  return o;
}

}  // namespace

TEST_CASE("core.retreat.halves_the_step_until_the_solve_succeeds", "[core][run][retreat]") {
  // Two failed attempts at iteration 3: RETREAT and UPDATE at 1/2, again at 1/4, then the solve
  // succeeds and the iteration's own UPDATE takes the full step again.
  const Outcome o = run_case("tp_step_failure: {fail_at: 3, failures: 2}\n");
  INFO(o.process.err);
  REQUIRE(o.process.exit_code == 0);
  CHECK(o.summary["status"] == "converged");
  CHECK(o.summary["iterations"] == 4);
  CHECK(o.steps ==
        "update 1 1\nupdate 2 1\nretreat 3\nupdate 3 0.5\nretreat 3\nupdate 3 0.25\nupdate 3 1\nupdate 4 1\n");
  CHECK_THAT(o.process.err, Contains("tp_step_failure.solve (iteration 3): deliberate step failure 1 at iteration 3; "
                                     "retreat 1 of at most 4") &&
                                Contains("retreat 2 of at most 4"));
  CHECK_THAT(o.process.out, Contains("iteration 3/100:") && Contains("2 retreat(s)"));
}

TEST_CASE("core.retreat.fails_after_max_retreats", "[core][run][retreat]") {
  // Failing every attempt: after run.max_retreats halvings the run fails, naming the cause and the count.
  const Outcome o = run_case("tp_step_failure: {fail_at: 2, failures: 10}\nrun: {max_retreats: 3}\n");
  CHECK(o.process.exit_code == 1);
  CHECK(o.summary["status"] == "failed");
  CHECK_THAT(o.summary["message"].get<std::string>(),
             Contains("deliberate step failure 4 at iteration 2") && Contains("halved 3 times") &&
                 Contains("run.max_retreats = 3"));
  CHECK(o.steps == "update 1 1\nretreat 2\nupdate 2 0.5\nretreat 2\nupdate 2 0.25\nretreat 2\nupdate 2 0.125\n");
}

TEST_CASE("core.retreat.not_at_the_first_iteration_nor_when_off", "[core][run][retreat]") {
  // Iteration 1 has no update to undo; max_retreats 0 turns retreating off; a RETREAT entry that
  // cannot undo its step fails the run with its own message.
  const Outcome first = run_case("tp_step_failure: {fail_at: 1}\n");
  CHECK(first.process.exit_code == 1);
  CHECK_THAT(first.summary["message"].get<std::string>(), Contains("deliberate step failure 1 at iteration 1"));
  CHECK(first.steps.empty());
  const Outcome off = run_case("tp_step_failure: {fail_at: 2}\nrun: {max_retreats: 0}\n");
  CHECK(off.process.exit_code == 1);
  CHECK(off.steps == "update 1 1\n");
  const Outcome refused = run_case("tp_step_failure: {fail_at: 2, retreats: false}\n");
  CHECK(refused.process.exit_code == 1);
  CHECK_THAT(refused.summary["message"].get<std::string>(),
             Contains("tp_step_failure.retreat (iteration 2)") && Contains("retreats are off"));
  // The refusal ends the loop at once: no second retreat is tried.
  CHECK_THAT(refused.process.err, Contains("retreat 1 of at most 4") && !Contains("retreat 2 of"));
}
