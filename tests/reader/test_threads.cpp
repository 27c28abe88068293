// Concurrent interpolation on one handle (datasets loaded lazily by whichever thread comes first,
// the held region filled then) and on several handles at once: the answers equal one thread's.
#include <catch2/catch.hpp>

#include <cmath>
#include <thread>

#include "reader_test.hpp"
#include "synth.hpp"

using reader_test::Points;
using reader_test::Random;
using reader_test::Reader;
using reader_test::work_path;

namespace {

const std::vector<std::string> all = {"alp",  "betax", "betay", "betaz", "gxx", "gxy",    "gyy",    "kxx",
                                      "kxy",  "kzz",   "rho",   "press", "eps", "vel[0]", "vel[1]", "vel[2]",
                                      "w_lorentz", "/variables/chi"};

std::string threads_file() {
  const std::string path = work_path("threads.h5");
  synth::Writer w(path);
  synth::GridSpec g;
  g.nx = g.ny = 41;
  g.nz = 21;
  g.dx = 0.05;
  g.origin = {-1, -1, 0};
  g.equatorial = true;
  w.header(g);
  static const synth::Held cube{"cube", {-0.4, 0.0, 0.0}, 0.12};
  const auto smooth = [](double a) {
    return [a](double x, double y, double z) { return std::sin(a * x + 0.3) * std::cos(y - a) * (1 + 0.2 * z * z); };
  };
  w.dataset("/variables/chi", {[](double x, double y, double z) { return 1 + 0.05 * std::exp(-(x * x + y * y + z * z)); }});
  w.dataset("/variables/eta", {[](double x, double, double) { return 0.9 + 0.02 * x; }});
  w.dataset("/ADMBase/alp", {smooth(0.5)});
  w.dataset("/ADMBase/betax", {smooth(0.7), 1, &cube});
  w.dataset("/ADMBase/betay", {smooth(0.9), 1, &cube});
  w.dataset("/ADMBase/betaz", {[](double x, double, double z) { return z * x; }, -1, &cube});
  for (const char* k : {"kxx", "kxy", "kzz"}) w.dataset(std::string("/ADMBase/") + k, {smooth(1.1)});
  w.dataset("/HydroBase/rho", {[](double x, double y, double z) {
              return 0.1 * std::max(0.0, 1 - ((x - 0.4) * (x - 0.4) + y * y + z * z) / 0.1);
            }});
  w.dataset("/HydroBase/vel[0]", {[](double, double y, double) { return -0.2 * y; }});
  w.dataset("/HydroBase/vel[1]", {[](double x, double, double) { return 0.2 * x; }});
  w.dataset("/HydroBase/vel[2]", {[](double, double, double) { return 0.0; }, -1});
  w.eos("piecewise_polytrope", {0, 0.05}, {1, 1 * std::pow(0.05, 2 - 2.5)}, {2, 2.5}, {0, 0});
  w.scalar("bh_bare_mass", 0.1);
  w.scalar("bh_position_x", -0.4);
  w.scalar("bh_position_y", 0.0);
  w.scalar("bh_position_z", 0.0);
  return path;
}

}  // namespace

TEST_CASE("reader.concurrent_interpolation_equals_one_thread", "[reader]") {
  const std::string path = threads_file();
  Random rnd(31);
  Points p;
  for (int i = 0; i < 4000; ++i) p.add(rnd.uniform(-0.95, 0.95), rnd.uniform(-0.95, 0.95), rnd.uniform(-0.95, 0.95));
  std::vector<std::vector<double>> expected;
  {
    const Reader one(path);
    expected = one.interpolate(all, p);
  }
  const Reader shared(path);  // fresh: nothing loaded yet, the threads race to load and fill
  constexpr int n_threads = 8;
  std::vector<std::vector<std::vector<double>>> got(n_threads);
  std::vector<std::string> errors(n_threads);
  std::vector<std::thread> threads;
  for (int t = 0; t < n_threads; ++t)
    threads.emplace_back([&, t] {
      try {
        // Each thread asks for the fields in another order, so that several load at once.
        std::vector<std::string> mine(all.begin() + t % 5, all.end());
        mine.insert(mine.end(), all.begin(), all.begin() + t % 5);
        const auto v = shared.interpolate(mine, p);
        got[t].resize(all.size());
        for (std::size_t f = 0; f < mine.size(); ++f) got[t][(f + t % 5) % all.size()] = v[f];
        // A second handle on the same file, in parallel with the others.
        const Reader own(path);
        const auto w = own.interpolate(all, p);
        if (w != expected) errors[t] = "a private handle differs";
      } catch (const std::exception& e) {
        errors[t] = e.what();
      }
    });
  for (auto& th : threads) th.join();
  for (int t = 0; t < n_threads; ++t) {
    INFO("thread " << t);
    CHECK(errors[t].empty());
    REQUIRE(got[t].size() == expected.size());
    for (std::size_t f = 0; f < all.size(); ++f) {
      INFO("field " << all[f]);
      CHECK(got[t][f] == expected[f]);  // bit for bit
    }
  }
}
