// bhnsid run --warm-start with tp_checkpoint (x <- x/2 + target/2, target steerable): a run started
// from a converged neighbour of another target takes the neighbour's x (the plugin's warm-start
// hook), ends at its own fixed point in fewer iterations than from its initial guess, and counts its
// own iterations; a neighbour with another non-steerable parameter, another build, no checkpoint,
// or the run's own directory is refused with one error line before anything is written.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const char* const parfile_text =
    "plugins: [tp_checkpoint]\ntp_checkpoint:\n  tolerance: 1.0e-9\n  wobble: 0\nrun:\n  max_iterations: 80\n"
    "  checkpoint_overhead: 1.0e9\n";

ProcessResult run(const fs::path& parfile, const fs::path& out, std::vector<std::string> extra = {}) {
  return run_parfile_with_test_plugins(parfile, out, std::move(extra));
}

json summary(const fs::path& run_dir) { return json::parse(read_file(run_dir / "summary.json")); }

struct Neighbour {
  TempDir dir;
  fs::path parfile, out;
  Neighbour() : parfile(dir.write("case.yaml", parfile_text)), out(dir.path() / "target3") {
    const ProcessResult r = run(parfile, out);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
  }
};

}  // namespace

TEST_CASE("core.warm_start.starts_from_a_converged_neighbour_of_another_steerable_value", "[core][run][warm]") {
  Neighbour nb;
  const fs::path cold = nb.dir.path() / "cold", warm = nb.dir.path() / "warm";
  REQUIRE(run(nb.parfile, cold, {"--set", "tp_checkpoint.target=3.01"}).exit_code == 0);
  const ProcessResult r = run(nb.parfile, warm, {"--set", "tp_checkpoint.target=3.01", "--warm-start", nb.out.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const json c = summary(cold), w = summary(warm);
  CHECK(w["status"] == "converged");
  // Both at the fixed point of target 3.01, to twice the tolerance (the map contracts by 1/2).
  CHECK(std::fabs(w["scalars"]["x"].get<double>() - 3.01) < 2e-9);
  CHECK(std::fabs(c["scalars"]["x"].get<double>() - 3.01) < 2e-9);
  // From x = 3 instead of x = 0: log2(3.01/0.01) ~ 8 fewer halvings.
  CHECK(w["iterations"].get<int>() + 5 <= c["iterations"].get<int>());
  // The warm run's own history: its steps count from 1, not from the neighbour's.
  CHECK(w["scalars"]["steps"].get<double>() == w["iterations"].get<double>());
  CHECK_THAT(read_file(warm / "log.txt"),
             Contains("warm start from") && Contains("tp_checkpoint.target 3") && Contains("-> 3.01"));
}

TEST_CASE("core.warm_start.refuses_what_is_not_a_steerable_neighbour", "[core][run][warm]") {
  Neighbour nb;
  const auto refused = [&](const fs::path& out, std::vector<std::string> extra, const std::string& says) {
    const ProcessResult r = run(nb.parfile, out, extra);
    INFO(r.err);
    CHECK(r.exit_code == 2);
    CHECK(line_count(r.err) == 1);
    CHECK_THAT(r.err, Contains(says));
    CHECK_FALSE(fs::exists(out));
  };
  // tolerance is not steerable: the error names the file, the key and both values.
  refused(nb.dir.path() / "a", {"--set", "tp_checkpoint.tolerance=1e-8", "--warm-start", nb.out.string()},
          "tp_checkpoint.tolerance");
  refused(nb.dir.path() / "b", {"--warm-start", (nb.dir.path() / "nowhere").string()}, "no checkpoint there");
  // Another build of the plugin.
  const fs::path plugins = nb.dir.path() / "plugins";
  fs::create_directories(plugins);
  fs::copy_file(test_plugin_dir() / "libbhnsid_tp_checkpoint.so", plugins / "libbhnsid_tp_checkpoint.so");
  { std::ofstream(plugins / "libbhnsid_tp_checkpoint.so", std::ios::app | std::ios::binary) << '\0'; }
  const ProcessResult other = run_bhnsid({"run", nb.parfile.string(), "--output", (nb.dir.path() / "c").string(),
                                          "--warm-start", nb.out.string(), "--plugin-path", plugins.string()});
  CHECK(other.exit_code == 2);
  CHECK_THAT(other.err, Contains("written by another build of bhnsid"));
  // Its own run directory (which --force would replace) and --resume together: refused.
  const std::string before = read_file(nb.out / "summary.json");
  const ProcessResult self = run(nb.parfile, nb.out, {"--force", "--warm-start", nb.out.string()});
  CHECK(self.exit_code == 2);
  CHECK_THAT(self.err, Contains("is the run directory of this run"));
  CHECK(read_file(nb.out / "summary.json") == before);
  const ProcessResult both = run(nb.parfile, nb.dir.path() / "d", {"--resume", "--warm-start", nb.out.string()});
  CHECK(both.exit_code == 2);
  CHECK_THAT(both.err, Contains("excludes"));
}

TEST_CASE("core.warm_start.from_the_next_coarser_run_refines_every_lattice_parameter_together", "[core][run][warm]") {
  Neighbour nb;  // points = 8, spacing = 0.5
  const fs::path finer = nb.dir.path() / "finer";
  const ProcessResult r =
      run(nb.parfile, finer, {"--set", "tp_checkpoint.points=16", "--set", "tp_checkpoint.spacing=0.25", "--warm-start",
                              nb.out.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(read_file(finer / "log.txt"), Contains("the next coarser lattice") && Contains("tp_checkpoint.points 8"));
  const auto refused = [&](const std::string& name, std::vector<std::string> sets, const std::string& says) {
    std::vector<std::string> extra;
    for (const auto& s : sets) extra.insert(extra.end(), {"--set", s});
    extra.insert(extra.end(), {"--warm-start", nb.out.string()});
    const ProcessResult bad = run(nb.parfile, nb.dir.path() / name, extra);
    INFO(bad.err);
    CHECK(bad.exit_code == 2);
    CHECK(line_count(bad.err) == 1);
    CHECK_THAT(bad.err, Contains(says));
    CHECK_FALSE(fs::exists(nb.dir.path() / name));
  };
  // Half a refinement (the count doubled, the spacing kept), two refinements, a coarsening.
  refused("a", {"tp_checkpoint.points=16"}, "refined in tp_checkpoint.points but not in tp_checkpoint.spacing");
  refused("b", {"tp_checkpoint.points=32", "tp_checkpoint.spacing=0.125"}, "the next coarser one");
  refused("c", {"tp_checkpoint.points=4", "tp_checkpoint.spacing=1"}, "tp_checkpoint.points");
}
