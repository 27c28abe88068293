// The puncture plugin's bad-input checks, through `bhnsid check` (exit 2, the key named).
#include <catch2/catch.hpp>

#include <string>

#include "process.hpp"

using namespace bhnsid::test;

namespace {

ProcessResult check_with(const std::string& puncture) {
  TempDir dir;
  const auto par = dir.write("p.yaml", "plugins: [grid, multigrid, puncture, hamiltonian]\n"
                                       "grid: {n: 32, dx: 0.5}\n"
                                       "puncture: " + puncture + "\n");
  return run_bhnsid({"check", par.string()});
}

}  // namespace

TEST_CASE("plugins.puncture.refuses_bad_input", "[plugins][puncture]") {
  // A puncture on a grid point (1/r infinite), outside the cube, with Mhat <= 0, or out of the
  // symmetry plane with equatorial symmetry is refused before anything runs, naming the key.
  const ProcessResult ok = check_with("{bare_mass: 1, position: [0.25, 0, 0], momentum: [0, 0.3, 0]}");
  INFO(ok.out << ok.err);
  CHECK(ok.exit_code == 0);
  const ProcessResult on_point = check_with("{bare_mass: 1, position: [0.5, 0, 0]}");
  CHECK(on_point.exit_code == 2);
  CHECK(on_point.err.find("puncture.position") != std::string::npos);
  CHECK(on_point.err.find("grid point") != std::string::npos);
  const ProcessResult outside = check_with("{bare_mass: 1, position: [9.1, 0, 0]}");
  CHECK(outside.exit_code == 2);
  CHECK(outside.err.find("outside the cube") != std::string::npos);
  const ProcessResult massless = check_with("{bare_mass: 0, position: [0.25, 0, 0]}");
  CHECK(massless.exit_code == 2);
  CHECK(massless.err.find("puncture.bare_mass") != std::string::npos);
  const ProcessResult off_plane = check_with("{bare_mass: 1, position: [0.25, 0, 0.1]}");
  CHECK(off_plane.exit_code == 2);
  CHECK(off_plane.err.find("equatorial") != std::string::npos);
}
