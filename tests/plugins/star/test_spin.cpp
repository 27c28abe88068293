// star_spin, the star's angular momentum about its rest-mass centroid. A single corotating star held
// at Omegahat = 0.025 spins with J = I Omega, Omega = Omegahat/sigma: in conformally flat maximal
// data with the minimal-distortion shift the O(Omega) part is Hartle's slowly rotating star, whose
// I = 0.0386475 for rho_c = 0.1 (Gamma = 2, K = 1) comes from scripts/hartle_inertia.py, an
// independent integration of the TOV and frame-dragging equations in areal coordinates (without the
// frame dragging, i.e. without the shift, 0.0471261).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <string>

#include "process.hpp"

using namespace bhnsid::test;
using Catch::Detail::Approx;

namespace {

/// static_star.yaml with the momentum constraint and the shift, so that the star drags its frame.
double spin_over_i_omega(const TempDir& dir, const std::string& name, double omega_hat, double inertia) {
  std::string par = read_file(source_dir() / "parfiles" / "static_star.yaml");
  const std::string plain = "lapse, star,";
  REQUIRE(par.find(plain) != std::string::npos);
  par.replace(par.find(plain), plain.size(), "lapse, momentum, shift, star,");
  const auto file = dir.write(name + ".yaml", par);
  const auto out = dir.path() / name;
  const ProcessResult r = run_bhnsid({"run", file.string(), "--output", out.string(), "--set",
                                      "star.test_omega_hat=" + std::to_string(omega_hat)});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto s = nlohmann::json::parse(read_file(out / "summary.json"))["scalars"];
  const double omega = omega_hat / s["sigma"].get<double>();
  INFO("star_spin = " << s["star_spin"].get<double>() << ", I Omega = " << inertia * omega
                      << ", J_z (faces) = " << s["angular_momentum_z"].get<double>());
  // The spin about the centroid is the whole angular momentum of a single star.
  CHECK(s["star_spin"].get<double>() == Approx(s["angular_momentum_z"].get<double>()).epsilon(0.02));
  return s["star_spin"].get<double>() / (inertia * omega);
}

}  // namespace

TEST_CASE("plugins.star.corotating_star_spins_with_its_moment_of_inertia", "[plugins][star]") {
  // Measured at n = 64, dx = 0.06: 0.997 (Omegahat = 0.025), 1.013 (0.05, the O(Omega^2) flattening).
  // The tolerance is the 8 %; a spin without frame dragging would be 1.22 I Omega.
  TempDir dir;
  CHECK(spin_over_i_omega(dir, "spin", 0.025, 0.0386475) == Approx(1.0).margin(0.08));
}
