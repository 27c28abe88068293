// A run of each kind killed by SIGKILL (between iterations, in the middle of an iteration's solve,
// during a checkpoint write) and resumed with --resume ends with the data.h5 of an uninterrupted
// run, to the bit: every field, every scalar, the loop's history. One thread: with several, OpenMP
// sums its partial reductions in arrival order, so two uninterrupted runs already differ in the
// last bit of a residual norm (docs/user-guide.md, "Resuming a run").
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <csignal>
#include <cstdlib>
#include <sstream>
#include <string>

#include "h5_read.hpp"
#include "process.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

const char* const datasets[] = {
    "ADMBase/alp",     "ADMBase/betax",      "ADMBase/betay",      "ADMBase/betaz",     "ADMBase/gxx",        "ADMBase/gxy",
    "ADMBase/gxz",     "ADMBase/gyz",        "ADMBase/kxx",        "ADMBase/kxy",       "ADMBase/kxz",        "ADMBase/kyy",
    "ADMBase/kyz",     "ADMBase/kzz",        "HydroBase/rho",      "HydroBase/press",   "HydroBase/eps",      "HydroBase/vel[0]",
    "HydroBase/vel[1]", "HydroBase/vel[2]",  "HydroBase/w_lorentz", "variables/chi",    "variables/eta",      "variables/wvec[0]",
    "variables/wvec[1]", "variables/wvec[2]", "variables/beta[0]",  "variables/beta[1]", "variables/beta[2]"};

struct KillAt {
  explicit KillAt(const std::string& where) { ::setenv("BHNSID_TEST_KILL", where.c_str(), 1); }
  ~KillAt() { ::unsetenv("BHNSID_TEST_KILL"); }
};

// The parameter file with tp_kill among its plugins, right after the grid: a kill in its
// checkpoint section lands after the grid's fields were written.
fs::path with_kill_plugin(const TempDir& dir, const std::string& parfile) {
  std::string text = read_file(source_dir() / "parfiles" / parfile);
  const std::size_t at = text.find("plugins: [grid,");
  REQUIRE(at != std::string::npos);
  text.insert(at + std::string("plugins: [grid,").size(), " tp_kill,");
  return dir.write(parfile, text);
}

ProcessResult run(const fs::path& parfile, const fs::path& out, const std::vector<std::string>& sets,
                  bool resume = false) {
  // Every iteration's checkpoint, however slow the machine (no time limit on their cost).
  std::vector<std::string> args = {"run", parfile.string(), "--output", out.string(), "--set", "run.threads=1",
                                   "--set", "run.checkpoint_overhead=1e9", "--plugin-path", test_plugin_dir().string()};
  for (const auto& s : sets) args.insert(args.end(), {"--set", s});
  if (resume) args.push_back("--resume");
  return run_bhnsid(args);
}

std::string history(const fs::path& run_dir) {
  // Without the wall-time columns, which no two runs share.
  std::istringstream in(read_file(run_dir / "scalars.tsv"));
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream cin(line);
    for (std::string c; std::getline(cin, c, '\t');) cells.push_back(c);
    rows.push_back(cells);
  }
  std::string out;
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size() && c < rows[0].size(); ++c)
      if (rows[0][c].find("seconds") == std::string::npos) out += row[c] + "\t";
    out += "\n";
  }
  return out;
}

void same_data(const fs::path& reference, const fs::path& resumed) {
  const H5Reader a((reference / "data.h5").string()), b((resumed / "data.h5").string());
  CHECK(b.text("/", "status") == "converged");
  int compared = 0;
  for (const char* name : datasets) {
    if (!a.exists(std::string("/") + name)) continue;
    INFO(name);
    std::array<hsize_t, 3> da{}, db{};
    const std::vector<double> va = a.dataset(std::string("/") + name, da), vb = b.dataset(std::string("/") + name, db);
    REQUIRE(da == db);
    std::size_t differing = 0;
    for (std::size_t p = 0; p < va.size(); ++p) differing += va[p] != vb[p];
    CHECK(differing == 0);
    ++compared;
  }
  CHECK(compared >= 5);
  // The excision cube the reader fills beta in, also after a resume that went straight to OUTPUT.
  if (a.exists_attribute("/ADMBase/betay", "held_region_centre")) {
    REQUIRE(b.exists_attribute("/ADMBase/betay", "held_region_centre"));
    CHECK(a.reals("/ADMBase/betay", "held_region_centre", 3) == b.reals("/ADMBase/betay", "held_region_centre", 3));
    CHECK(a.real("/ADMBase/betay", "held_region_half_size") == b.real("/ADMBase/betay", "held_region_half_size"));
  }
  const auto sa = nlohmann::json::parse(read_file(reference / "summary.json"));
  const auto sb = nlohmann::json::parse(read_file(resumed / "summary.json"));
  CHECK(sa["iterations"] == sb["iterations"]);
  for (const auto& [key, value] : sa["scalars"].items()) {
    if (key.find("seconds") != std::string::npos) continue;
    INFO(key);
    CHECK(sb["scalars"][key] == value);
  }
  CHECK(history(reference) == history(resumed));
}

void kill_and_resume(const std::string& parfile, const std::vector<std::string>& sets,
                     const std::vector<std::string>& kills) {
  TempDir dir;
  const fs::path file = with_kill_plugin(dir, parfile);
  const ProcessResult ref = run(file, dir.path() / "reference", sets);
  INFO(ref.err);
  REQUIRE(ref.exit_code == 0);
  const int iterations = nlohmann::json::parse(read_file(dir.path() / "reference" / "summary.json"))["iterations"];
  for (const std::string& kill : kills) {
    INFO("BHNSID_TEST_KILL=" << kill << " of a run of " << iterations << " iterations");
    if (kill != "analysis") REQUIRE(std::stoi(kill.substr(kill.find(':') + 1)) < iterations);
    const fs::path out = dir.path() / ("killed_" + std::to_string(&kill - kills.data()));
    {
      KillAt at(kill);
      REQUIRE(run(file, out, sets).signal == SIGKILL);
    }
    CHECK_FALSE(fs::exists(out / "data.h5"));
    const ProcessResult r = run(file, out, sets, true);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(read_file(out / "log.txt"), Contains("resumed from"));
    same_data(dir.path() / "reference", out);
  }
}

}  // namespace

TEST_CASE("plugins.io_hdf5.killed_binary_resumes_to_the_same_data", "[plugins][io_hdf5][resume]") {
  // The quickstart binary converges in 28 iterations: killed early (the star still moving), late,
  // and while its ninth checkpoint was being written.
  kill_and_resume("quickstart.yaml", {}, {"solve:3", "solve:21", "save:9", "analysis"});
}

TEST_CASE("plugins.io_hdf5.killed_static_star_and_boosted_puncture_resume_to_the_same_data", "[plugins][io_hdf5][resume]") {
  kill_and_resume("static_star.yaml", {"grid.n=32", "grid.dx=0.12"}, {"solve:4"});
  // One iteration: killed after its (converged) checkpoint, in ANALYSIS.
  kill_and_resume("boosted_puncture.yaml", {"grid.n=16", "grid.dx=2.5"}, {"analysis"});
}
