// The computed fields on synthetic files: the puncture's pole added exactly, the EOS consistency,
// the Lorentz factor from the returned metric, the harmonic fill of a held region, absent = zero.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "reader_test.hpp"
#include "synth.hpp"

using reader_test::Points;
using reader_test::Random;
using reader_test::Reader;
using reader_test::work_path;

namespace {

constexpr double bh_mass = 0.5;
constexpr double bh[3] = {0.031, -0.017, 0.0};  // off the points, in the equatorial plane
double chi_exact(double x, double y, double z) { return 1 + 0.1 * std::exp(-(x * x + 2 * y * y + z * z)) + 0.02 * x; }
double eta_exact(double x, double y, double z) { return 1 - 0.2 * std::exp(-(x * x + y * y + 0.5 * z * z)); }

/// [-n dx / 2, n dx / 2]^2 x [0, n dx / 2], stored; n even.
synth::GridSpec equatorial_grid(int n, double dx) {
  synth::GridSpec g;
  g.nx = g.ny = n + 1;
  g.nz = n / 2 + 1;
  g.dx = dx;
  g.origin = {-dx * (n / 2), -dx * (n / 2), 0};
  g.equatorial = true;
  return g;
}

std::string puncture_file() {
  const std::string path = work_path("puncture.h5");
  synth::Writer w(path);
  w.header(equatorial_grid(24, 0.1));
  w.dataset("/variables/chi", {chi_exact});
  w.dataset("/variables/eta", {eta_exact});
  // Stored alp and gxx are deliberately wrong: with a puncture the reader must not use them.
  w.dataset("/ADMBase/alp", {[](double, double, double) { return 7.0; }});
  w.dataset("/ADMBase/gxx", {[](double, double, double) { return 7.0; }});
  w.scalar("bh_bare_mass", bh_mass);
  w.scalar("bh_position_x", bh[0]);
  w.scalar("bh_position_y", bh[1]);
  w.scalar("bh_position_z", bh[2]);
  return path;
}

// Three pieces with continuous P, and eps offsets a_i making eps continuous (Read et al.'s rule).
struct Eos {
  std::vector<double> lo{0, 0.02, 0.06}, k{0.8, 0, 0}, gamma{1.6, 2.4, 3.0}, a{0, 0, 0};
  Eos() {
    for (std::size_t i = 1; i < lo.size(); ++i) {
      k[i] = k[i - 1] * std::pow(lo[i], gamma[i - 1] - gamma[i]);
      a[i] = a[i - 1] + k[i - 1] * std::pow(lo[i], gamma[i - 1] - 1) / (gamma[i - 1] - 1) -
             k[i] * std::pow(lo[i], gamma[i] - 1) / (gamma[i] - 1);
    }
  }
};

double star_rho(double x, double y, double z) { return 0.1 * std::max(0.0, 1 - (x * x + y * y + z * z) / 0.36); }

}  // namespace

TEST_CASE("reader.puncture_pole_is_added_exactly", "[reader]") {
  const Reader r(puncture_file());
  Random rnd(5);
  Points p;
  for (double dist : {1e-6, 1e-4, 1e-3, 0.01, 0.03, 0.07, 0.15})
    for (int i = 0; i < 8; ++i) {
      const double th = rnd.uniform(0, M_PI), ph = rnd.uniform(0, 2 * M_PI);
      p.add(bh[0] + dist * std::sin(th) * std::cos(ph), bh[1] + dist * std::sin(th) * std::sin(ph), bh[2] + dist * std::cos(th));
    }
  const auto v = r.interpolate({"gxx", "gyy", "gzz", "gxy", "gyz", "alp", "/variables/chi", "/variables/eta"}, p);
  double chi_err = 0, phi_err = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double dx = p.x[i] - bh[0], dy = p.y[i] - bh[1], dz = p.z[i] - bh[2];
    const double rad = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double pole = bh_mass / (2 * rad);
    const double chi = chi_exact(p.x[i], p.y[i], p.z[i]);
    // phi recovered from gxx differs from the exact one by chi's interpolation error alone.
    const double phi = std::pow(v[0][i], 0.25);
    phi_err = std::max(phi_err, std::fabs(phi - pole - chi));
    chi_err = std::max(chi_err, std::fabs(v[6][i] - chi));
    REQUIRE(phi - pole == Approx(v[6][i]).margin(1e-12 * phi));
    REQUIRE(v[0][i] == Approx(std::pow(pole + v[6][i], 4)).epsilon(1e-14));
    REQUIRE(v[1][i] == v[0][i]);
    REQUIRE(v[2][i] == v[0][i]);
    REQUIRE(v[3][i] == 0.0);
    REQUIRE(v[4][i] == 0.0);
    REQUIRE(v[5][i] == Approx(v[7][i] / (pole + v[6][i])).epsilon(1e-14));
    REQUIRE(v[5][i] == Approx(eta_exact(p.x[i], p.y[i], p.z[i]) / (pole + chi)).epsilon(1e-4));
  }
  std::printf("puncture: max |phi - M/2r - chi_exact| = %.3e, max chi interpolation error %.3e\n", phi_err, chi_err);
  CHECK(chi_err < 1e-4);
  CHECK(phi_err < chi_err * (1 + 1e-6) + 1e-12);

  // Exactly at the puncture: an error for the metric, with a message; no Inf.
  Points at;
  at.add(bh[0], bh[1], bh[2]);
  for (const char* f : {"gxx", "alp"}) {
    const reader_test::Result e = r.try_interpolate({f}, at);
    CHECK(e.status == BHNSID_READER_ERR_PUNCTURE);
    CHECK_THAT(e.message, Catch::Contains("puncture"));
  }
  // Where phi^4 would overflow the call fails as well; chi alone is fine there.
  Points near;
  near.add(bh[0] + 1e-80, bh[1], bh[2]);
  CHECK(r.try_interpolate({"gxx"}, near).status == BHNSID_READER_ERR_PUNCTURE);
  CHECK(r.try_interpolate({"/variables/chi"}, at).status == BHNSID_READER_OK);
}

TEST_CASE("reader.eos_consistency_piecewise_polytrope", "[reader]") {
  const Eos eos;
  const std::string path = work_path("eos_pieces.h5");
  {
    synth::Writer w(path);
    w.header(equatorial_grid(20, 0.08));
    w.dataset("/HydroBase/rho", {star_rho});
    w.dataset("/HydroBase/vel[0]", {[](double, double y, double) { return -0.3 * y; }});
    w.dataset("/HydroBase/vel[1]", {[](double x, double, double) { return 0.3 * x + 0.05; }});
    w.dataset("/HydroBase/vel[2]", {[](double, double, double z) { return 0.1 * z; }, -1});
    for (const char* g : {"gxx", "gyy", "gzz"})
      w.dataset(std::string("/ADMBase/") + g, {[](double x, double, double) { return 1.2 + 0.1 * x; }});
    for (const char* g : {"gxy", "gyz"}) w.dataset(std::string("/ADMBase/") + g, {[](double, double, double) { return 0.0; }});
    w.dataset("/ADMBase/gxz", {[](double, double, double z) { return 0.01 * z; }, -1});
    w.dataset("/ADMBase/alp", {[](double, double, double) { return 0.8; }});
    w.eos("piecewise_polytrope", eos.lo, eos.k, eos.gamma, eos.a);
  }
  const Reader r(path);
  Random rnd(17);
  Points p;
  for (int i = 0; i < 3000; ++i) p.add(rnd.uniform(-0.75, 0.75), rnd.uniform(-0.75, 0.75), rnd.uniform(-0.75, 0.75));
  const auto v = r.interpolate({"rho", "press", "eps", "vel[0]", "vel[1]", "vel[2]", "w_lorentz", "gxx", "gxz", "gyy",
                                "gzz", "/HydroBase/rho"}, p);
  int per_piece[3] = {0, 0, 0}, vacuum = 0, clamped = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double rho = v[0][i];
    REQUIRE(rho >= 0);
    if (v[11][i] < 0) {
      ++clamped;
      REQUIRE(rho == 0.0);
    }
    if (rho == 0) {
      ++vacuum;
      REQUIRE(v[1][i] == 0.0);
      REQUIRE(v[2][i] == 0.0);
      REQUIRE(v[3][i] == 0.0);
      REQUIRE(v[6][i] == 1.0);
      continue;
    }
    const std::size_t piece = rho >= eos.lo[2] ? 2 : rho >= eos.lo[1] ? 1 : 0;
    ++per_piece[piece];
    // The same formula on the same double: equal to the last bit.
    REQUIRE(v[1][i] == eos.k[piece] * std::pow(rho, eos.gamma[piece]));
    REQUIRE(v[2][i] == eos.a[piece] + eos.k[piece] * std::pow(rho, eos.gamma[piece] - 1) / (eos.gamma[piece] - 1));
    // W from the returned metric and velocity.
    const double vx = v[3][i], vy = v[4][i], vz = v[5][i];
    const double v2 = v[7][i] * vx * vx + v[9][i] * vy * vy + v[10][i] * vz * vz + 2 * v[8][i] * vx * vz;
    REQUIRE(v[6][i] == Approx(1 / std::sqrt(1 - v2)).epsilon(1e-14));
  }
  std::printf("eos: points per piece %d %d %d, vacuum %d (of which clamped from < 0: %d)\n", per_piece[0], per_piece[1],
              per_piece[2], vacuum, clamped);
  CHECK(per_piece[0] > 20);
  CHECK(per_piece[1] > 20);
  CHECK(per_piece[2] > 20);
  CHECK(clamped > 0);  // the kink at the surface overshoots: the clamp was exercised
}

TEST_CASE("reader.eos_without_formulas_refuses_press_and_eps", "[reader]") {
  for (const std::string model : {"", "tabulated"}) {
    const std::string path = work_path("eos_none.h5");
    {
      synth::Writer w(path);
      w.header(equatorial_grid(12, 0.1));
      w.dataset("/HydroBase/rho", {star_rho});
      for (int c = 0; c < 3; ++c)
        w.dataset("/HydroBase/vel[" + std::to_string(c) + "]", {[](double, double, double) { return 0.0; }, c == 2 ? -1 : 1});
      w.eos(model, {0}, {1}, {2}, {0});
    }
    const Reader r(path);
    Points p;
    p.add(0.05, 0.02, 0.01);
    for (const char* f : {"press", "eps"}) {
      const reader_test::Result e = r.try_interpolate({"rho", f}, p);
      CHECK(e.status == BHNSID_READER_ERR_EOS);
      CHECK_THAT(e.message, Catch::Contains(f) && Catch::Contains("rho is available"));
    }
    CHECK(r.at("rho", 0.05, 0.02, 0.01) > 0.09);
    // press and eps are not offered for this file.
    std::size_t n = 0;
    bhnsid_reader_num_fields(r.get(), &n);
    for (std::size_t i = 0; i < n; ++i) {
      const char* name = nullptr;
      bhnsid_reader_field_name(r.get(), i, &name);
      CHECK(std::string(name) != "press");
    }
  }
}

TEST_CASE("reader.held_region_is_filled_harmonically", "[reader]") {
  // A linear shift with garbage in the held region: the harmonic fill reproduces a linear field,
  // so the reader's values inside equal it to the solver's tolerance.
  const auto bx = [](double x, double y, double) { return 0.3 + 0.2 * x - 0.1 * y + 0.04 * x * y; };
  const auto bz = [](double x, double, double z) { return 0.2 * z + 0.1 * x * z; };  // odd in z, harmonic
  synth::Held cube{"cube", {0.02, 0.01, 0.0}, 0.25};
  synth::Held sphere{"sphere", {-0.1, 0.05, 0.0}, 0.22};
  const std::string path = work_path("held.h5");
  const auto garbage = [&](const synth::Held& h, const synth::Fn& f) -> synth::Fn {
    return [h, f](double x, double y, double z) {
      const double d[3] = {x - h.centre[0], y - h.centre[1], z - h.centre[2]};
      const bool in = h.shape == "cube" ? std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])}) <= h.half_size
                                        : std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) <= h.half_size;
      return in ? 99.0 : f(x, y, z);
    };
  };
  {
    synth::Writer w(path);
    w.header(equatorial_grid(24, 0.05));
    w.dataset("/ADMBase/betax", {garbage(cube, bx), 1, &cube});
    w.dataset("/ADMBase/betaz", {garbage(cube, bz), -1, &cube});
    w.dataset("/ADMBase/betay", {garbage(sphere, bx), 1, &sphere});
    w.dataset("/variables/beta[0]", {garbage(cube, bx), 1});  // no attributes: left as stored
  }
  const Reader r(path);
  Points p;
  Random rnd(23);
  for (int i = 0; i < 300; ++i) p.add(rnd.uniform(-0.3, 0.3), rnd.uniform(-0.3, 0.3), rnd.uniform(-0.3, 0.3));
  const auto v = r.interpolate({"betax", "betaz", "betay", "/variables/beta[0]"}, p);
  double ex = 0, ez = 0, ey = 0, raw = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    ex = std::max(ex, std::fabs(v[0][i] - bx(p.x[i], p.y[i], p.z[i])));
    ez = std::max(ez, std::fabs(v[1][i] - bz(p.x[i], p.y[i], p.z[i])));
    ey = std::max(ey, std::fabs(v[2][i] - bx(p.x[i], p.y[i], p.z[i])));
    raw = std::max(raw, std::fabs(v[3][i] - bx(p.x[i], p.y[i], p.z[i])));
  }
  std::printf("held region: max error of the fill %.2e (cube) %.2e (odd, cube) %.2e (sphere); unfilled %.1f\n", ex, ez,
              ey, raw);
  // x y and x z are harmonic too (discretely exact): the fill reproduces the field to round-off.
  CHECK(ex < 1e-12);
  CHECK(ez < 1e-12);
  CHECK(ey < 1e-12);
  CHECK(raw > 50);  // without the attributes the garbage stays (and the check can tell)
}

TEST_CASE("reader.absent_fields_are_zero", "[reader]") {
  const std::string path = work_path("absent.h5");
  {
    synth::Writer w(path);
    w.header(equatorial_grid(12, 0.1));
    w.dataset("/ADMBase/alp", {[](double x, double, double) { return 0.9 + 0.01 * x; }});
    w.dataset("/ADMBase/gxx", {[](double, double, double) { return 1.5; }});
    w.link("/ADMBase/gxx", "/ADMBase/gyy");
    w.link("/ADMBase/gxx", "/ADMBase/gzz");
    for (const char* g : {"gxy", "gxz", "gyz"}) w.dataset(std::string("/ADMBase/") + g, {[](double, double, double) { return 0.0; }});
  }
  const Reader r(path);
  Points p;
  p.add(0.11, -0.23, -0.31);
  const std::vector<std::string> zero = {"betax", "betay", "betaz", "kxx", "kxy", "kzz", "rho", "press", "eps", "vel[0]", "vel[2]"};
  const auto v = r.interpolate(zero, p);
  for (std::size_t f = 0; f < zero.size(); ++f) CHECK(v[f][0] == 0.0);
  CHECK(r.at("w_lorentz", 0.11, -0.23, -0.31) == 1.0);
  CHECK(r.at("gzz", 0.11, -0.23, -0.31) == Approx(1.5).epsilon(1e-15));
  CHECK(r.at("alp", 0.11, -0.23, -0.31) == Approx(0.9 + 0.0011).epsilon(1e-14));
  std::size_t n = 0;
  bhnsid_reader_num_fields(r.get(), &n);
  CHECK(n == 23);  // every ETK field is answerable: absent ones are zero
  std::size_t nd = 0;
  bhnsid_reader_num_datasets(r.get(), &nd);
  CHECK(nd == 7);  // gyy and gzz (links) listed as datasets too
}
