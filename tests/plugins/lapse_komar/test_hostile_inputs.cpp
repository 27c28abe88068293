// Nonsense parameters of the lapse and horizon plugins and of the settings that tie them together,
// each on the lone hole of parfiles/boosted_puncture_komar.yaml (n = 16): every one ends in a clear
// error with the expected exit code (2: refused input before anything runs; 1: a run that failed and
// says why), naming what it refuses, never an internal error or a crash.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "process.hpp"
#include "star_runs.hpp"

using namespace bhnsid::test;

TEST_CASE("plugins.lapse_komar.hostile_parameters_end_in_clear_errors", "[plugins][lapse_komar][horizon]") {
  struct Case {
    std::vector<std::string> sets;
    int exit_code;
    std::string says;
  };
  const std::vector<Case> cases{
      {{"lapse_komar.condition=keplerian"}, 2, "lapse_komar.condition"},
      {{"lapse_komar.virial_tolerance=0"}, 2, "lapse_komar.virial_tolerance"},
      {{"lapse_komar.virial_tolerance=nan"}, 2, "lapse_komar.virial_tolerance"},
      {{"lapse_komar.initial_eta_regular=-1"}, 2, "lapse_komar.initial_eta_regular"},
      {{"horizon.l_max=1"}, 2, "horizon.l_max"},
      {{"horizon.l_max=1000"}, 2, "horizon.l_max"},
      {{"horizon.initial_radius=-0.5"}, 2, "horizon.initial_radius"},
      {{"horizon.tolerance=inf"}, 2, "horizon.tolerance"},
      {{"momentum.weight=eta"}, 2, "momentum.weight"},
      {{"puncture.mass_target=horizon"}, 2, "puncture.mass_target"},
      {{"puncture.mass_target=irreducible"}, 2, "holds the hole of a binary"},
      // The sampled box reaching past the grid, a search that cannot converge in one step, a box
      // smaller than the horizon: failed runs naming why.
      {{"horizon.search_radius=100"}, 1, "leaves the grid"},
      {{"horizon.max_iterations=1", "puncture.momentum=[0,0.3,0]"}, 1, "not converged in horizon.max_iterations = 1"},
      {{"horizon.initial_radius=0.1", "horizon.search_radius=0.3"}, 1, "horizon: no apparent horizon found"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> sets{"grid.n=16", "grid.dx=2.5"};
    sets.insert(sets.end(), c.sets.begin(), c.sets.end());
    const ParfileRun r = run_parfile("boosted_puncture_komar.yaml", sets);
    INFO(c.sets.front() << ":\n" << r.output);
    CHECK(r.exit_code == c.exit_code);
    CHECK(r.output.find(c.says) != std::string::npos);
    CHECK(r.output.find("internal error") == std::string::npos);
  }
}

TEST_CASE("plugins.lapse_komar.two_lapses_are_refused", "[plugins][lapse_komar]") {
  // One slicing per run: both lapse plugins listed is refused before anything runs, naming both.
  TempDir dir;
  const auto par = dir.write("two.yaml", "plugins: [grid, multigrid, puncture, hamiltonian, lapse, lapse_komar]\n"
                                         "puncture: {bare_mass: 1.0, position: [0.1, 0, 0]}\n");
  const ProcessResult r = run_bhnsid({"check", par.string()});
  INFO(r.out << r.err);
  CHECK(r.exit_code == 2);
  CHECK((r.out + r.err).find("both implement capability 'lapse'") != std::string::npos);
}
