// The level hierarchy (plugins/grid/hierarchy.cpp) for the paper's grids, the coarsening rule and
// its limits, and the plugin's parameters as a user sets them in a parameter file.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "bhnsid/core/errors.hpp"
#include "hierarchy.hpp"
#include "test_level.hpp"
#include "process.hpp"

using namespace bhnsid;
using namespace bhnsid::grid;
using Catch::Matchers::Contains;

namespace {

struct Config {
  int n;
  double dx;
};

// physics-notes §5.1: the three runs of each mass ratio (mu = 1, 3 and mu = 10) and the IRE's
// coarsest grid (64, 0.06).
const std::vector<Config> paper_configs = {{256, 0.015}, {128, 0.03}, {160, 0.015},   {256, 0.01},
                                           {128, 0.02},  {160, 0.014375}, {64, 0.06}};

std::vector<Level> hierarchy(int n, double dx, Symmetry symmetry, int max_levels = 0, int min_coarse = 4) {
  HierarchySpec spec;
  spec.n = n;
  spec.dx = dx;
  spec.symmetry = symmetry;
  spec.max_levels = max_levels;
  spec.min_coarse_intervals = min_coarse;
  return build_hierarchy(spec);
}

std::vector<int> intervals(const std::vector<Level>& levels) {
  std::vector<int> n;
  for (const Level& lv : levels) n.push_back(lv.n);
  return n;
}

}  // namespace

TEST_CASE("plugins.grid.hierarchy_paper_configurations", "[plugins][grid]") {
  // For every (n, dx) of physics-notes §5.1, with and without equatorial symmetry, every level is a
  // vertex-centred grid of the same cube [-n dx/2, n dx/2]^3: dx doubles and n halves per level,
  // coarse point I sits exactly (bit for bit) where fine point 2I sits, so restriction by injection
  // and the IRE's comparison between resolutions see the same coordinates; with equatorial symmetry
  // only z >= 0 is stored (nz = n/2 + 1, z(0) = 0); the origin is a grid point of every even level
  // (to round-off, see below);
  // one ghost layer surrounds the stored points (at(-1,-1,-1) = 0, at(nx,ny,nz) = size - 1).
  // Coarsening continues down to n = 4 (min_coarse_intervals default 4) or an odd n: 160 = 5 x 2^5
  // reaches n = 5 without symmetry, but only n = 10 with it (n = 5 has no whole z >= 0 half).
  for (const Config& c : paper_configs)
    for (const Symmetry sym : {Symmetry::none, Symmetry::equatorial}) {
      const bool eq = sym == Symmetry::equatorial;
      INFO("n = " << c.n << ", dx = " << c.dx << (eq ? ", equatorial" : ", no symmetry"));
      const std::vector<Level> levels = hierarchy(c.n, c.dx, sym);
      const int coarsest = c.n == 160 ? (eq ? 10 : 5) : 4;
      REQUIRE(levels.front().n == c.n);
      CHECK(levels.back().n == coarsest);
      const double h = 0.5 * c.n * c.dx;
      for (std::size_t l = 0; l < levels.size(); ++l) {
        const Level& lv = levels[l];
        INFO("level " << l << ", n = " << lv.n);
        CHECK(lv.index == static_cast<int>(l));
        CHECK(lv.z_symmetry == eq);
        CHECK(lv.half_width() == Approx(h).epsilon(1e-15));
        CHECK(lv.nx == lv.n + 1);
        CHECK(lv.ny == lv.n + 1);
        CHECK(lv.nz == (eq ? lv.n / 2 + 1 : lv.n + 1));
        CHECK(lv.x(0) == Approx(-h).epsilon(1e-15));
        CHECK(lv.x(lv.nx - 1) == Approx(h).epsilon(1e-14));
        CHECK(lv.y(0) == Approx(-h).epsilon(1e-15));
        CHECK(lv.z(lv.nz - 1) == Approx(h).epsilon(1e-14));
        if (eq) CHECK(lv.origin[2] == 0.0);
        else CHECK(lv.z(0) == Approx(-h).epsilon(1e-15));
        if (lv.n % 2 == 0) {
          // Zero up to the rounding of h: with -march=native the compiler fuses origin + dx i into an
          // FMA, which keeps the exact product dx n/2 and so leaves h's rounding error (~1e-18 for
          // dx = 0.014375). Coordinates of coincident points still agree bit for bit (below).
          CHECK(std::fabs(lv.x(lv.n / 2)) <= 1e-15 * h);
          CHECK(std::fabs(lv.y(lv.n / 2)) <= 1e-15 * h);
          CHECK(std::fabs(lv.z(eq ? 0 : lv.n / 2)) <= 1e-15 * h);
        }
        CHECK(lv.sy == lv.nx + 2);
        CHECK(lv.sz == lv.sy * (lv.ny + 2));
        CHECK(lv.size == static_cast<std::size_t>(lv.sz * (lv.nz + 2)));
        CHECK(lv.at(-1, -1, -1) == 0);
        CHECK(lv.at(lv.nx, lv.ny, lv.nz) == static_cast<std::ptrdiff_t>(lv.size) - 1);
        if (l == 0) {
          CHECK(lv.dx == c.dx);
          continue;
        }
        const Level& fine = levels[l - 1];
        CHECK(lv.n * 2 == fine.n);
        CHECK(lv.dx == 2 * fine.dx);
        int mismatches = 0;
        for (int i = 0; i < lv.nx; ++i) mismatches += lv.x(i) != fine.x(2 * i) || lv.y(i) != fine.y(2 * i);
        for (int k = 0; k < lv.nz; ++k) mismatches += lv.z(k) != fine.z(2 * k);
        CHECK(mismatches == 0);
      }
    }
}

TEST_CASE("plugins.grid.hierarchy_rejects_bad_n", "[plugins][grid]") {
  // An odd n (or n < 2) puts neither the origin nor the axes on grid points: core::InputError (exit
  // 2), naming the parameter grid.n so that the user knows what to change.
  for (const int n : {161, 63, 1, 0, -4}) {
    INFO("n = " << n);
    CHECK_THROWS_AS(hierarchy(n, 0.015, Symmetry::none), core::InputError);
    CHECK_THROWS_WITH(hierarchy(n, 0.015, Symmetry::equatorial), Contains("grid.n"));
  }
  CHECK_NOTHROW(hierarchy(2, 0.5, Symmetry::none));
}

TEST_CASE("plugins.grid.hierarchy_limits", "[plugins][grid]") {
  // max_levels caps the count (finest included) and min_coarse_intervals stops coarsening before a
  // level would have fewer intervals; whichever stops first wins. Expected lists: 256 halved down to
  // the bound, by hand.
  CHECK(intervals(hierarchy(256, 0.015, Symmetry::none, 3)) == std::vector<int>{256, 128, 64});
  CHECK(intervals(hierarchy(256, 0.015, Symmetry::none, 1)) == std::vector<int>{256});
  CHECK(intervals(hierarchy(256, 0.015, Symmetry::none, 20)) == std::vector<int>{256, 128, 64, 32, 16, 8, 4});
  CHECK(intervals(hierarchy(256, 0.015, Symmetry::none, 0, 16)) == std::vector<int>{256, 128, 64, 32, 16});
  CHECK(intervals(hierarchy(256, 0.015, Symmetry::none, 0, 17)) == std::vector<int>{256, 128, 64, 32});
  CHECK(intervals(hierarchy(256, 0.015, Symmetry::equatorial, 0, 2)) ==
        std::vector<int>{256, 128, 64, 32, 16, 8, 4, 2});
  CHECK(intervals(hierarchy(256, 0.015, Symmetry::none, 4, 32)) == std::vector<int>{256, 128, 64, 32});
  CHECK(intervals(hierarchy(256, 0.015, Symmetry::none, 2, 32)) == std::vector<int>{256, 128});
  // 6 = 2 x 3: without symmetry n = 3 is a level (if allowed), with it coarsening stops at 6.
  CHECK(intervals(hierarchy(12, 0.1, Symmetry::none, 0, 3)) == std::vector<int>{12, 6, 3});
  CHECK(intervals(hierarchy(12, 0.1, Symmetry::equatorial, 0, 3)) == std::vector<int>{12, 6});
}

TEST_CASE("plugins.grid.plugin_builds_the_hierarchy_from_parameters", "[plugins][grid]") {
  // Through the executable: the plugin reads n, dx, symmetry, max_levels and min_coarse_intervals
  // and logs one line per level; n = 160 reaches n = 5 without symmetry and stops at n = 10 (five
  // levels) with it (physics-notes §5.1: 160 = 5 x 2^5); an odd n is bad input (exit 2) naming grid.n.
  test::TempDir dir;
  auto run = [&](const std::string& name, const std::string& grid_section) {
    const auto parfile = dir.write(name + ".yaml", "plugins: [grid]\ngrid:\n" + grid_section);
    return test::run_bhnsid({"run", parfile.string(), "--output", (dir.path() / name).string()});
  };
  const test::ProcessResult none = run("none", "  n: 160\n  dx: 0.015\n  symmetry: none\n");
  INFO(none.err);
  REQUIRE(none.exit_code == 0);
  const std::string log_none = test::read_file(dir.path() / "none" / "log.txt");
  CHECK_THAT(log_none, Contains("level 5: n =    5, dx = 0.48, 6 x 6 x 6 points"));
  CHECK_THAT(log_none, Contains("MiB in grid fields and masks"));

  const test::ProcessResult eq = run("eq", "  n: 160\n  dx: 0.015\n  symmetry: equatorial\n");
  INFO(eq.err);
  REQUIRE(eq.exit_code == 0);
  const std::string log_eq = test::read_file(dir.path() / "eq" / "log.txt");
  CHECK_THAT(log_eq, Contains("level 4: n =   10, dx = 0.24, 11 x 11 x 6 points (z >= 0)"));
  CHECK_THAT(log_eq, !Contains("level 5"));

  const test::ProcessResult limited =
      run("limited", "  n: 64\n  dx: 0.06\n  max_levels: 2\n  min_coarse_intervals: 2\n");
  INFO(limited.err);
  REQUIRE(limited.exit_code == 0);
  const std::string log_limited = test::read_file(dir.path() / "limited" / "log.txt");
  CHECK_THAT(log_limited, Contains("level 1: n =   32, dx = 0.12, 33 x 33 x 17 points (z >= 0)"));
  CHECK_THAT(log_limited, !Contains("level 2"));

  const test::ProcessResult odd = run("odd", "  n: 161\n");
  CHECK(odd.exit_code == core::exit_input);
  CHECK_THAT(odd.err, Contains("grid.n"));
}

TEST_CASE("plugins.grid.check_refuses_a_bad_hierarchy_before_any_run", "[plugins][grid]") {
  // The hierarchy is checked in PARAMCHECK, which `bhnsid check` runs and `bhnsid run` runs before
  // it creates the run directory: an odd grid.n is exit 2 from both, the message names the file
  // and the key, and no run directory is left behind.
  using namespace bhnsid::test;
  TempDir dir;
  const auto par = dir.write("odd.yaml", "plugins: [grid]\ngrid:\n  n: 63\n");
  const ProcessResult check = run_bhnsid({"check", par.string()});
  CHECK(check.exit_code == 2);
  CHECK_THAT(check.err, Contains(par.string()) && Contains("grid.n = 63"));
  const auto out = dir.path() / "odd";
  const ProcessResult run = run_bhnsid({"run", par.string(), "--output", out.string()});
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Contains("grid.n = 63"));
  CHECK_FALSE(std::filesystem::exists(out));
  const ProcessResult good = run_bhnsid({"check", par.string(), "--set", "grid.n=64"});
  CHECK(good.exit_code == 0);
}

TEST_CASE("plugins.grid.level_indices_near_covers_an_interval", "[plugins][grid]") {
  // Level::indices_near gives the stored indices along an axis that a coordinate interval can
  // hold (the excision masks loop over only these): every index whose coordinate lies in [lo, hi]
  // is in [first, last], an interval off the level gives an empty range, and the range is clamped.
  const Level lv = test::make_level(8, 0.5, true);  // x, y in [-2, 2], z in [0, 2]
  for (int axis = 0; axis < 3; ++axis) {
    const int extent = axis == 0 ? lv.nx : axis == 1 ? lv.ny : lv.nz;
    for (double lo = -3.1; lo < 3; lo += 0.13)
      for (double width : {0.0, 0.2, 0.5, 1.7}) {
        const double hi = lo + width;
        const auto r = lv.indices_near(axis, lo, hi);
        CHECK(r[0] >= 0);
        CHECK(r[1] <= extent - 1);
        int missed = 0;
        for (int i = 0; i < extent; ++i) {
          const double x = lv.origin[static_cast<std::size_t>(axis)] + lv.dx * i;
          if (x >= lo && x <= hi) missed += i < r[0] || i > r[1];
        }
        INFO("axis " << axis << ", [" << lo << ", " << hi << "]");
        CHECK(missed == 0);
      }
    const auto above = lv.indices_near(axis, 10, 11), below = lv.indices_near(axis, -11, -10);
    CHECK(above[0] > above[1]);
    CHECK(below[0] > below[1]);
    const auto all = lv.indices_near(axis, -100, 100);
    CHECK(all[0] == 0);
    CHECK(all[1] == extent - 1);
  }
  // indices_near_box: under equatorial symmetry a box below z = 0 stands for its mirror image
  // above, whose stored points its z range must cover; without symmetry it covers no stored point.
  const auto box = lv.indices_near_box({-0.3, 0.2, -1.1}, {0.4, 0.9, -0.6});
  CHECK(box[0] == lv.indices_near(0, -0.3, 0.4));
  CHECK(box[1] == lv.indices_near(1, 0.2, 0.9));
  int z_missed = 0;
  for (int k = 0; k < lv.nz; ++k) z_missed += lv.z(k) >= 0.6 && lv.z(k) <= 1.1 && (k < box[2][0] || k > box[2][1]);
  CHECK(z_missed == 0);
  const Level full = test::make_level(8, 0.5, false);
  const auto plain = full.indices_near_box({-0.3, 0.2, -1.1}, {0.4, 0.9, -0.6});
  CHECK(full.z(plain[2][1]) < 0.6);  // one index of slack above -0.6, far from the image
}

TEST_CASE("plugins.grid.nested_boxes_double_outward", "[plugins][grid]") {
  // grid.boxes = 3: three boxes of n intervals about the origin at dx, 2 dx, 4 dx (half widths 0.8,
  // 1.6, 3.2), the inner two marked inner, then the outermost box coarsened as a single cube is.
  HierarchySpec spec;
  spec.n = 16;
  spec.dx = 0.1;
  spec.symmetry = Symmetry::equatorial;
  spec.boxes = 3;
  const std::vector<Level> levels = build_hierarchy(spec);
  REQUIRE(levels.size() == 5);
  CHECK(intervals(levels) == std::vector<int>{16, 16, 16, 8, 4});
  for (std::size_t l = 0; l < 3; ++l) {
    CHECK(levels[l].half_width() == Approx(0.8 * std::pow(2.0, static_cast<double>(l))));
    CHECK(levels[l].inner == (l < 2));
  }
  CHECK(levels[4].half_width() == Approx(3.2));
  // The part of box 1 that box 0 covers: its point (I, J, K) is box 1's point at box 0's (2I, 2J,
  // 2K), the same coordinates, at the array index of box 1's point (I + n/4, J + n/4, K).
  const Level part = covered_part(levels[1], levels[0]);
  CHECK(part.nx == 9);
  CHECK(part.nz == 5);
  for (int K = 0; K < part.nz; ++K)
    for (int I = 0; I < part.nx; ++I) {
      CHECK(part.at(I, I, K) == levels[1].at(I + 4, I + 4, K));
      CHECK(part.x(I) == Approx(levels[0].x(2 * I)));
      CHECK(levels[1].x(I + 4) == Approx(levels[0].x(2 * I)));
      CHECK(part.z(K) == Approx(levels[0].z(2 * K)));
    }
  // A coarsening of one cube: the part is the coarse level itself.
  const Level same = covered_part(levels[3], levels[2]);
  CHECK(same.offset == levels[3].offset);
  CHECK(same.nx == levels[3].nx);
}

TEST_CASE("plugins.grid.single_cube_plugins_refuse_nested_boxes", "[plugins][grid]") {
  // Plugins that read the finest level as the whole domain refuse nested boxes with one input
  // error naming grid.boxes, before the solve.
  using namespace bhnsid::test;
  TempDir dir;
  const ProcessResult run = run_bhnsid({"run", (source_dir() / "parfiles" / "quickstart.yaml").string(), "--output",
                                        (dir.path() / "qs").string(), "--set", "grid.boxes=2"});
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err + run.out, Contains("grid.boxes = 2: the plugin") && Contains("works on a single cube only"));
}
