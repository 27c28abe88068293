// data.h5 and data.xdmf of real runs, read back with the HDF5 C API alone: the Einstein Toolkit's
// fields are there, finite, compressed, in physical units, and consistent with the stated EOS, with
// the Valencia velocity's definition and with maximal slicing; a failed run is marked failed; a
// non-finite field is never written.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <csignal>
#include <cmath>
#include <map>
#include <string>

#include "h5_read.hpp"
#include "process.hpp"

using namespace bhnsid::test;
using Catch::Matchers::Contains;

namespace {

const char* const adm[] = {"alp", "betax", "betay", "betaz", "gxx", "gxy", "gxz", "gyy",
                           "gyz", "gzz", "kxx", "kxy", "kxz", "kyy", "kyz", "kzz"};
const char* const hydro[] = {"rho", "press", "eps", "vel[0]", "vel[1]", "vel[2]", "w_lorentz"};

}  // namespace

TEST_CASE("plugins.io_hdf5.binary_data_file_is_complete_and_consistent", "[plugins][io_hdf5]") {
  TempDir dir;
  const auto parfile = source_dir() / "parfiles" / "quickstart.yaml";
  const auto out = dir.path() / "run";
  const ProcessResult r = run_bhnsid({"run", parfile.string(), "--output", out.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_FALSE(std::filesystem::exists(out / "data.h5.partial"));
  const H5Reader f((out / "data.h5").string());
  CHECK(f.text("/", "format") == "bhnsid-data");
  CHECK(f.integer("/", "format_version") == 1);
  CHECK(f.text("/", "status") == "converged");
  CHECK(f.text("/grid", "symmetry") == "equatorial");
  CHECK(f.text("/parameters", "parameter_file") == read_file(parfile));
  CHECK_THAT(f.text("/parameters", "resolved"), Contains("io_hdf5:") && Contains("compression: 1"));
  CHECK_THAT(f.text("/eos", "description"), Contains("polytrope Gamma=2 K=1"));
  CHECK(f.text("/provenance", "git_revision").size() > 0);
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"))["scalars"];
  for (const char* key : {"rest_mass", "adm_mass", "omega", "bh_bare_mass", "angular_momentum", "binding_energy"})
    CHECK(f.real("/scalars", key) == summary[key].get<double>());

  // Physical coordinates: x = sigma xhat.
  const double sigma = f.real("/grid", "sigma"), dx = f.real("/grid", "dx");
  CHECK(sigma == summary["sigma"].get<double>());
  CHECK(dx == Approx(sigma * 0.12).epsilon(1e-14));
  const std::vector<double> origin = f.reals("/grid", "origin_xyz", 3);
  CHECK(origin[2] == 0.0);  // the stored half z >= 0

  std::array<hsize_t, 3> dims{};
  std::map<std::string, std::vector<double>> v;
  for (const char* name : adm) {
    INFO(name);
    v[name] = f.dataset(std::string("/ADMBase/") + name, dims);
    CHECK(dims == std::array<hsize_t, 3>{17, 33, 33});
    for (double x : v[name]) REQUIRE(std::isfinite(x));
    const auto filters = f.filters(std::string("/ADMBase/") + name);
    CHECK(filters == std::vector<H5Z_filter_t>{H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE});
  }
  for (const char* name : hydro) {
    INFO(name);
    v[name] = f.dataset(std::string("/HydroBase/") + name, dims);
    for (double x : v[name]) REQUIRE(std::isfinite(x));
  }
  CHECK(f.integer("/ADMBase/betaz", "parity_z") == -1);
  CHECK(f.integer("/ADMBase/kxz", "parity_z") == -1);
  CHECK(f.text("/ADMBase/kxx", "units") == "1/length");

  const double omega = f.real("/scalars", "omega");
  int star_points = 0;
  double rho_max = 0;
  for (hsize_t k = 0; k < dims[0]; ++k)
    for (hsize_t j = 0; j < dims[1]; ++j)
      for (hsize_t i = 0; i < dims[2]; ++i) {
        const std::size_t p = (k * dims[1] + j) * dims[2] + i;
        const double x = origin[0] + dx * i, y = origin[1] + dx * j;
        // Conformally flat, and maximal slicing: K = gamma^ij K_ij = (kxx + kyy + kzz)/gxx = 0.
        REQUIRE(v["gyy"][p] == v["gxx"][p]);
        REQUIRE(v["gzz"][p] == v["gxx"][p]);
        REQUIRE(v["gxy"][p] == 0.0);
        const double trace = v["kxx"][p] + v["kyy"][p] + v["kzz"][p];
        REQUIRE(std::fabs(trace) <= 1e-12 * (std::fabs(v["kxx"][p]) + std::fabs(v["kyy"][p]) + 1e-300));
        const double rho = v["rho"][p];
        rho_max = std::max(rho_max, rho);
        if (!(rho > 0)) {
          REQUIRE(v["press"][p] == 0.0);
          REQUIRE(v["vel[1]"][p] == 0.0);
          REQUIRE(v["w_lorentz"][p] == 1.0);
          continue;
        }
        ++star_points;
        // The stated EOS (Gamma = 2, K = 1): P = rho^2, eps = K rho^(Gamma-1)/(Gamma-1) = rho.
        REQUIRE(v["press"][p] == Approx(rho * rho).epsilon(1e-14));
        REQUIRE(v["eps"][p] == Approx(rho).epsilon(1e-14));
        // Valencia v^i = (beta^i + Omega xi^i)/alpha, xi = (-y, x, 0), in physical units.
        REQUIRE(v["vel[0]"][p] == Approx((v["betax"][p] - omega * y) / v["alp"][p]).epsilon(1e-12));
        REQUIRE(v["vel[1]"][p] == Approx((v["betay"][p] + omega * x) / v["alp"][p]).epsilon(1e-12));
        // W = (1 - gamma_ij v^i v^j)^(-1/2).
        const double v2 = v["gxx"][p] * (v["vel[0]"][p] * v["vel[0]"][p] + v["vel[1]"][p] * v["vel[1]"][p] +
                                         v["vel[2]"][p] * v["vel[2]"][p]);
        REQUIRE(v["w_lorentz"][p] * v["w_lorentz"][p] * (1 - v2) == Approx(1.0).epsilon(1e-12));
      }
  CHECK(star_points > 20);
  // The EOS by its formulas, for a reader that recomputes P and eps from rho.
  CHECK(f.text("/eos", "model") == "piecewise_polytrope");
  CHECK(f.reals("/eos", "K", 1) == std::vector<double>{1.0});
  CHECK(f.reals("/eos", "Gamma", 1) == std::vector<double>{2.0});
  CHECK(f.reals("/eos", "rho0_lo", 1) == std::vector<double>{0.0});
  // The excision cube about the puncture, where beta is the held beta_0 (one value) and not solved.
  CHECK(f.text("/ADMBase/betay", "held_region_shape") == "cube");
  const std::vector<double> centre = f.reals("/ADMBase/betay", "held_region_centre", 3);
  const double half = f.real("/ADMBase/betay", "held_region_half_size");
  CHECK(centre[0] == Approx(f.real("/scalars", "bh_position_x")).epsilon(1e-12));
  CHECK(centre[1] == 0.0);
  CHECK(half > dx);
  int held_points = 0;
  double held_value = 0;
  for (hsize_t k = 0; k < dims[0]; ++k)
    for (hsize_t j = 0; j < dims[1]; ++j)
      for (hsize_t i = 0; i < dims[2]; ++i) {
        const double x = origin[0] + dx * i, y = origin[1] + dx * j, z = dx * k;
        if (std::fabs(x - centre[0]) > half || std::fabs(y - centre[1]) > half || std::fabs(z - centre[2]) > half) continue;
        const double b = v["betay"][(k * dims[1] + j) * dims[2] + i];
        if (held_points++ == 0) held_value = b;
        REQUIRE(b == held_value);
      }
  CHECK(held_points >= 8);
  CHECK(held_value != 0.0);
  CHECK_FALSE(f.exists_attribute("/ADMBase/alp", "held_region_shape"));
  CHECK(rho_max <= 0.1);
  CHECK(rho_max > 0.09);
  // The solver's unknowns, for a reader that adds the puncture's 1/r exactly.
  CHECK(f.exists("/variables/chi"));
  CHECK(f.exists("/variables/wvec[2]"));
  CHECK_FALSE(f.exists("/variables/matter_energy"));

  const std::string xdmf = read_file(out / "data.xdmf");
  CHECK_THAT(xdmf, Contains("3DCoRectMesh") && Contains("data.h5:/ADMBase/alp") && Contains("data.h5:/HydroBase/vel[1]") &&
                       Contains("Name=\"bhnsid_chi\""));
}

TEST_CASE("plugins.io_hdf5.every_run_kind_and_a_failed_run", "[plugins][io_hdf5]") {
  TempDir dir;
  struct Case {
    const char* parfile;
    std::vector<std::string> sets;
    int exit_code;
    const char* status;
  };
  const Case cases[] = {
      // The static star: no shift or curvature is solved, so none is written (docs/output-format.md).
      {"static_star.yaml", {"--set", "grid.n=32", "--set", "grid.dx=0.12"}, 0, "converged"},
      {"boosted_puncture.yaml", {"--set", "grid.n=16", "--set", "grid.dx=2.5"}, 0, "converged"},
      {"quickstart.yaml", {"--set", "run.max_iterations=3"}, 1, "failed"},
  };
  for (const Case& c : cases) {
    INFO(c.parfile);
    const auto out = dir.path() / c.parfile;
    std::vector<std::string> args{"run", (source_dir() / "parfiles" / c.parfile).string(), "--output", out.string()};
    args.insert(args.end(), c.sets.begin(), c.sets.end());
    const ProcessResult r = run_bhnsid(args);
    INFO(r.err);
    REQUIRE(r.exit_code == c.exit_code);
    const H5Reader f((out / "data.h5").string());
    CHECK(f.text("/", "status") == c.status);
    CHECK(f.exists("/ADMBase/alp"));
    CHECK(f.exists("/ADMBase/gxx"));
    const bool star = std::string(c.parfile) != "boosted_puncture.yaml";
    const bool shift = std::string(c.parfile) != "static_star.yaml";
    CHECK(f.exists("/HydroBase/rho") == star);
    CHECK(f.exists("/ADMBase/betax") == shift);
    CHECK(f.exists("/ADMBase/kxx") == shift);
    if (c.exit_code != 0) CHECK_THAT(f.text("/", "failure"), Contains("run.max_iterations = 3"));
    if (!star) {
      // The hole of parfiles/boosted_puncture.yaml: position (0.1, 0, 0), momentum (0, 0.3, 0), sigma = 1.
      CHECK(f.real("/scalars", "bh_position_x") == 0.1);
      CHECK(f.real("/scalars", "bh_position_y") == 0.0);
      CHECK(f.real("/scalars", "bh_position_z") == 0.0);
      CHECK(f.real("/scalars", "bh_momentum_y") == 0.3);
      CHECK(f.real("/grid", "sigma") == 1.0);
    }
  }
}

TEST_CASE("plugins.io_hdf5.non_finite_field_is_never_written", "[plugins][io_hdf5]") {
  TempDir dir;
  const auto parfile = dir.write("nan.yaml", "plugins: [grid, tp_nan_export, io_hdf5]\ngrid: {n: 8, dx: 0.5}\n");
  const auto out = dir.path() / "run";
  const ProcessResult r =
      run_bhnsid({"run", parfile.string(), "--output", out.string(), "--plugin-path", test_plugin_dir().string()});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("io_hdf5.write") && Contains("/TestBase/nan_field is nan at point (1, 2, 3)") &&
                        Contains("data.h5 is not written"));
  CHECK_FALSE(std::filesystem::exists(out / "data.h5"));
  CHECK_FALSE(std::filesystem::exists(out / "data.h5.partial"));
  CHECK_FALSE(std::filesystem::exists(out / "data.xdmf"));
}

TEST_CASE("plugins.io_hdf5.interrupted_run_is_marked_interrupted", "[plugins][io_hdf5][signals]") {
  // SIGTERM during the first field solve (after the initial data): the run stops between multigrid
  // cycles, and data.h5 holds that last state marked "interrupted", not "converged".
  TempDir dir;
  const auto out = dir.path() / "run";
  Background run({"run", (source_dir() / "parfiles" / "boosted_puncture.yaml").string(), "--output", out.string(),
                  "--set", "grid.n=96", "--set", "grid.dx=0.4166666666666667", "--set", "multigrid.tau_factor=1e-9"});
  REQUIRE(wait_for_text(out / "log.txt.partial", "solving 4 equation(s) together", 120));
  run.signal(SIGTERM);
  const ProcessResult r = run.wait(120);
  INFO(r.out << r.err);
  CHECK(r.exit_code == 143);
  const H5Reader f((out / "data.h5").string());
  CHECK(f.text("/", "status") == "interrupted");
  CHECK(f.text("/", "failure").empty());
}

TEST_CASE("plugins.io_hdf5.a_refused_write_is_an_error_not_a_crash", "[plugins][io_hdf5]") {
  // With a file-size limit (ulimit -f, a full disk) the refused data.h5 write was reported, and then
  // HDF5's exit handler crashed closing the half-written file again: exit 139, no summary.json.
  TempDir dir;
  const auto out = dir.path() / "run";
  const ProcessResult r = run_bhnsid({"run", (source_dir() / "parfiles" / "quickstart.yaml").string(), "--output",
                                      out.string(), "--set", "run.checkpoint_every=0"},
                                     {}, 2L << 20);
  INFO(r.err);
  CHECK(r.signal == 0);
  CHECK((r.exit_code == 1 || r.exit_code == 2));
  CHECK_THAT(r.err, Contains("data.h5"));
  CHECK(std::filesystem::exists(out / "summary.json"));
  CHECK_FALSE(std::filesystem::exists(out / "data.h5"));
  CHECK_FALSE(std::filesystem::exists(out / "data.h5.partial"));
}
