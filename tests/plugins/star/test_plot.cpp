// bhnsid plot: the binary's pictures from its plugin's plot script, and the refusals.
#include <catch2/catch.hpp>

#include <filesystem>

#include "process.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;

TEST_CASE("plugins.star.plot_draws_the_equator_and_the_outer_iteration", "[plugins][star][plot]") {
  TempDir dir;
  const auto run = dir.path() / "run";
  REQUIRE(run_bhnsid({"run", (source_dir() / "parfiles" / "quickstart.yaml").string(), "--output", run.string()})
              .exit_code == 0);
  const ProcessResult r = run_bhnsid({"plot", run.string()});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Contains("1 of 1 plot script(s) succeeded"));
  // PNG files of a real size (a blank 990 x 900 figure compresses to a few kB).
  for (const char* name : {"equator.png", "outer_iteration.png"}) {
    INFO(name);
    const auto png = run / "plots" / name;
    REQUIRE(std::filesystem::exists(png));
    CHECK(std::filesystem::file_size(png) > 20000);
    CHECK(read_file(png).substr(1, 3) == "PNG");
  }

  // Not a run directory; a run whose plugins draw nothing.
  const ProcessResult none = run_bhnsid({"plot", dir.path().string()});
  CHECK(none.exit_code == 2);
  CHECK_THAT(none.err, Contains("not a run directory (no params.yaml)"));
  const auto demo = dir.path() / "demo";
  REQUIRE(run_bhnsid({"run", (source_dir() / "parfiles" / "demo_poisson1d.yaml").string(), "--output", demo.string()})
              .exit_code == 0);
  const ProcessResult nothing = run_bhnsid({"plot", demo.string()});
  CHECK(nothing.exit_code == 2);
  CHECK_THAT(nothing.err, Contains("none of the run's plugins (demo_poisson1d) ships a plot script"));
}
