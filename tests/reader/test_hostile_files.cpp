// What a careless user or a damaged disk hands the library: a FIFO or a device where data.h5
// belongs, dimensions no memory holds, a held region larger than any grid, a point extrapolated
// to far beyond the grid. Each is an error code whose message names the cause, at once.
#include <catch2/catch.hpp>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstring>

#include "reader_test.hpp"
#include "synth.hpp"

using reader_test::Points;
using reader_test::Reader;
using reader_test::work_path;

namespace {

struct Outcome {
  bool finished = false;
  int status = -1;
  std::string message;
};

/// bhnsid_reader_open(path) in a child process, given `seconds`: one that waits on a FIFO is
/// killed and reported as unfinished, and the test goes on.
Outcome open_in_child(const std::string& path, int seconds) {
  int pipe_fds[2];
  REQUIRE(::pipe(pipe_fds) == 0);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::close(pipe_fds[0]);
    bhnsid_reader* r = nullptr;
    const int s = bhnsid_reader_open(path.c_str(), &r);
    const char* m = bhnsid_reader_last_error();
    if (::write(pipe_fds[1], m, std::strlen(m)) < 0) _exit(100);
    _exit(s);
  }
  ::close(pipe_fds[1]);
  Outcome o;
  for (int i = 0; i < seconds * 20 && !o.finished; ++i) {
    int st = 0;
    if (::waitpid(pid, &st, WNOHANG) == pid) {
      o.finished = true;
      o.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    } else {
      ::usleep(50000);
    }
  }
  if (!o.finished) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
  }
  char buffer[4096];
  ssize_t n = 0;
  while ((n = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0) o.message.append(buffer, static_cast<std::size_t>(n));
  ::close(pipe_fds[0]);
  return o;
}

synth::GridSpec small_grid() {
  synth::GridSpec g;
  g.nx = g.ny = g.nz = 9;
  g.dx = 0.1;
  g.origin = {-0.4, -0.4, -0.4};
  return g;
}

std::string held_file(const std::string& name, double centre, double half_size) {
  const std::string path = work_path(name);
  synth::Writer w(path);
  w.header(small_grid());
  synth::Held held;
  held.centre = {centre, centre, centre};
  held.half_size = half_size;
  w.dataset("/ADMBase/betax", {[](double x, double, double) { return x; }, 1, &held});
  return path;
}

}  // namespace

TEST_CASE("reader.fifos_and_devices_are_refused_at_once", "[reader]") {
  const std::string fifo = work_path("fifo_data.h5");
  ::unlink(fifo.c_str());
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  Outcome o = open_in_child(fifo, 5);
  CHECK(o.finished);  // not waiting for a writer
  CHECK(o.status == BHNSID_READER_ERR_IO);
  CHECK_THAT(o.message, Catch::Contains("fifo_data.h5 is a FIFO, not a regular file"));
  ::unlink(fifo.c_str());

  o = open_in_child("/dev/zero", 5);
  CHECK(o.finished);
  CHECK(o.status == BHNSID_READER_ERR_IO);
  CHECK_THAT(o.message, Catch::Contains("/dev/zero is a device, not a regular file"));
}

TEST_CASE("reader.dimensions_no_memory_holds_are_an_error_naming_the_dataset", "[reader]") {
  const std::string path = work_path("huge_dimensions.h5");
  {
    synth::Writer w(path);
    synth::GridSpec g;
    g.nx = g.ny = g.nz = 1000000;
    w.header(g);
  }
  {  // a chunked dataset of those dimensions: a few kB on disk, 8 EB in memory
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hsize_t dims[3] = {1000000, 1000000, 1000000}, chunk[3] = {8, 8, 8};
    const hid_t space = H5Screate_simple(3, dims, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 3, chunk);
    const hid_t group = H5Gcreate2(f, "/ADMBase", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t d = H5Dcreate2(f, "/ADMBase/alp", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    REQUIRE(d >= 0);
    H5Dclose(d);
    H5Gclose(group);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Fclose(f);
  }
  const Reader r(path);
  Points p;
  p.add(0.1, 0.1, 0.1);
  const reader_test::Result e = r.try_interpolate({"alp"}, p);
  CHECK(e.status == BHNSID_READER_ERR_INTERNAL);
  CHECK_THAT(e.message, Catch::Contains("out of memory: /ADMBase/alp holds 1000000 x 1000000 x 1000000 doubles"));
}

TEST_CASE("reader.held_region_larger_than_the_grid_is_refused_at_any_size", "[reader]") {
  // 1e6 and 1e300 cover the grid alike; 1e300 used to overflow the index box and pass unfilled.
  for (double half_size : {1e6, 1e300, 1.7e308}) {
    INFO("half-size " << half_size);
    const Reader r(held_file("held_huge.h5", 0.0, half_size));
    Points p;
    p.add(0.1, 0.1, 0.1);
    const reader_test::Result e = r.try_interpolate({"betax"}, p);
    CHECK(e.status == BHNSID_READER_ERR_FORMAT);
    CHECK_THAT(e.message, Catch::Contains("covers the whole grid"));
  }
  // Far away, it holds no point of the grid: nothing to fill, the stored values as they are.
  const Reader far(held_file("held_far.h5", 1e300, 1.0));
  CHECK(far.at("betax", 0.1, 0.0, 0.0) == Approx(0.1).margin(1e-14));
}

TEST_CASE("reader.extrapolation_far_outside_names_its_cause", "[reader]") {
  const std::string path = work_path("extrapolated_puncture.h5");
  constexpr double bh_x = 0.031;
  {
    synth::Writer w(path);
    w.header(small_grid());
    // A cubic in x that turns negative far out: the edge stencil reproduces it exactly there.
    w.dataset("/variables/chi", {[](double x, double y, double) { return 1 + 0.1 * x - 0.3 * x * x * x + 0.01 * y * y; }});
    w.dataset("/variables/eta", {[](double, double, double) { return 0.9; }});
    w.scalar("bh_bare_mass", 0.2);
    w.scalar("bh_position_x", bh_x);
    w.scalar("bh_position_y", 0.0);
    w.scalar("bh_position_z", 0.0);
  }
  const Reader r(path);
  Points far;
  far.add(100.0, 0.0, 0.0);
  reader_test::Result e = r.try_interpolate({"gxx"}, far, 4, BHNSID_READER_OUTSIDE_EXTRAPOLATE);
  CHECK(e.status == BHNSID_READER_ERR_OUTSIDE);
  CHECK_THAT(e.message, Catch::Contains("too far outside the grid") && !Catch::Contains("at the puncture"));

  Points very_far;
  very_far.add(1e300, 0.0, 0.0);
  e = r.try_interpolate({"/variables/chi"}, very_far, 4, BHNSID_READER_OUTSIDE_EXTRAPOLATE);
  CHECK(e.status == BHNSID_READER_ERR_OUTSIDE);
  CHECK_THAT(e.message, Catch::Contains("is not finite there"));

  // Near the grid extrapolation still works, and the puncture itself is still the puncture.
  Points near;
  near.add(0.45, 0.0, 0.0);
  CHECK(r.try_interpolate({"gxx", "alp"}, near, 4, BHNSID_READER_OUTSIDE_EXTRAPOLATE).status == BHNSID_READER_OK);
  Points at;
  at.add(bh_x, 0.0, 0.0);
  CHECK(r.try_interpolate({"gxx"}, at).status == BHNSID_READER_ERR_PUNCTURE);
}
