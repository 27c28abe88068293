// Bad input: each an error code with a message, never a crash, an abort or output on stderr.
#include <catch2/catch.hpp>

#include <fstream>
#include <thread>

#include "reader_test.hpp"
#include "synth.hpp"

using reader_test::Points;
using reader_test::Reader;
using reader_test::work_path;

namespace {

struct OpenResult {
  int status;
  std::string message;
};

OpenResult try_open(const std::string& path) {
  bhnsid_reader* r = nullptr;
  const int s = bhnsid_reader_open(path.c_str(), &r);
  OpenResult out{s, bhnsid_reader_last_error()};
  if (s == BHNSID_READER_OK) {
    bhnsid_reader_close(r);
    out.message.clear();
  } else {
    CHECK(r == nullptr);
  }
  return out;
}

std::string small_file(const std::string& name, const std::string& format = "bhnsid-data", long long version = 1) {
  const std::string path = work_path(name);
  synth::Writer w(path);
  synth::GridSpec g;
  g.nx = g.ny = g.nz = 6;
  g.dx = 0.2;
  g.origin = {-0.5, -0.5, -0.5};
  w.header(g, format, version);
  w.dataset("/ADMBase/alp", {[](double x, double, double) { return 1 + x; }});
  return path;
}

}  // namespace

TEST_CASE("reader.bad_files_are_refused_with_a_message", "[reader]") {
  OpenResult r = try_open(work_path("does_not_exist.h5"));
  CHECK(r.status == BHNSID_READER_ERR_IO);
  CHECK_THAT(r.message, Catch::Contains("no such file") && Catch::Contains("does_not_exist.h5"));

  const std::string text = work_path("not_hdf5.h5");
  std::ofstream(text) << "this is not HDF5\n";
  r = try_open(text);
  CHECK(r.status == BHNSID_READER_ERR_IO);
  CHECK_THAT(r.message, Catch::Contains("not an HDF5 file"));

  r = try_open(READER_TEST_DIR);
  CHECK(r.status == BHNSID_READER_ERR_IO);
  CHECK_THAT(r.message, Catch::Contains("directory"));

  r = try_open(small_file("other_format.h5", "something-else"));
  CHECK(r.status == BHNSID_READER_ERR_FORMAT);
  CHECK_THAT(r.message, Catch::Contains("'something-else'"));

  r = try_open(small_file("newer.h5", "bhnsid-data", 2));
  CHECK(r.status == BHNSID_READER_ERR_FORMAT);
  CHECK_THAT(r.message, Catch::Contains("format_version 2 is newer"));

  r = try_open(small_file("older.h5", "bhnsid-data", 0));
  CHECK(r.status == BHNSID_READER_ERR_FORMAT);
  CHECK_THAT(r.message, Catch::Contains("format_version 0 is not supported"));

  {  // HDF5, but no format attribute at all
    const hid_t f = H5Fcreate(work_path("bare.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    H5Fclose(f);
  }
  r = try_open(work_path("bare.h5"));
  CHECK(r.status == BHNSID_READER_ERR_FORMAT);
  CHECK_THAT(r.message, Catch::Contains("not a bhnsid data.h5"));

  CHECK(try_open(small_file("good.h5")).status == BHNSID_READER_OK);
}

TEST_CASE("reader.bad_requests_are_errors", "[reader]") {
  const Reader r(small_file("requests.h5"));
  Points p;
  p.add(0.1, 0.1, 0.1);

  reader_test::Result e = r.try_interpolate({"alp", "nonsense"}, p);
  CHECK(e.status == BHNSID_READER_ERR_ARGUMENT);
  CHECK_THAT(e.message, Catch::Contains("unknown field 'nonsense'"));

  e = r.try_interpolate({"/variables/chi"}, p);
  CHECK(e.status == BHNSID_READER_ERR_NOT_FOUND);
  CHECK_THAT(e.message, Catch::Contains("/variables/chi"));

  e = r.try_interpolate({"gxx"}, p);  // no metric stored and no puncture
  CHECK(e.status == BHNSID_READER_ERR_NOT_FOUND);

  for (int order : {0, 3, 10, -2}) {
    e = r.try_interpolate({"alp"}, p, order);
    CHECK(e.status == BHNSID_READER_ERR_ARGUMENT);
    CHECK_THAT(e.message, Catch::Contains("order"));
  }
  e = r.try_interpolate({"alp"}, p, 8);  // 6 points per axis: too few for 8
  CHECK(e.status == BHNSID_READER_ERR_ARGUMENT);
  CHECK_THAT(e.message, Catch::Contains("fewer than"));
  e = r.try_interpolate({"alp"}, p, 4, 7);
  CHECK(e.status == BHNSID_READER_ERR_ARGUMENT);

  Points out;
  out.add(0.1, 0.1, 0.1);
  out.add(0.1, 0.9, 0.1);
  e = r.try_interpolate({"alp"}, out);
  CHECK(e.status == BHNSID_READER_ERR_OUTSIDE);
  CHECK_THAT(e.message, Catch::Contains("point 1") && Catch::Contains("y must lie in"));

  Points nan;
  nan.add(0.1, std::nan(""), 0.1);
  e = r.try_interpolate({"alp"}, nan);
  CHECK(e.status == BHNSID_READER_ERR_ARGUMENT);
  CHECK_THAT(e.message, Catch::Contains("not finite"));

  // Null pointers and bad indices.
  CHECK(bhnsid_reader_interpolate(nullptr, nullptr, 0, nullptr, nullptr, nullptr, 0, nullptr, nullptr) ==
        BHNSID_READER_ERR_ARGUMENT);
  CHECK_THAT(bhnsid_reader_last_error(), Catch::Contains("handle"));
  const char* name = "alp";
  double v = 0;
  double* outv[1] = {&v};
  CHECK(bhnsid_reader_interpolate(r.get(), nullptr, 1, nullptr, p.y.data(), p.z.data(), 1, &name, outv) ==
        BHNSID_READER_ERR_ARGUMENT);
  CHECK(bhnsid_reader_open(nullptr, nullptr) == BHNSID_READER_ERR_ARGUMENT);
  const char* s = nullptr;
  CHECK(bhnsid_reader_field_name(r.get(), 99, &s) == BHNSID_READER_ERR_ARGUMENT);
  CHECK(bhnsid_reader_dataset_name(r.get(), 99, &s) == BHNSID_READER_ERR_ARGUMENT);
  CHECK(bhnsid_reader_scalar(r.get(), "adm_mass", &v) == BHNSID_READER_ERR_NOT_FOUND);
  CHECK(bhnsid_reader_string_attribute(r.get(), "/eos", "description", &s) == BHNSID_READER_ERR_NOT_FOUND);
  CHECK(bhnsid_reader_string_attribute(r.get(), "/grid", "dx", &s) == BHNSID_READER_ERR_FORMAT);
  CHECK_THAT(bhnsid_reader_last_error(), Catch::Contains("not a string"));
  std::size_t count = 0;
  CHECK(bhnsid_reader_numeric_attribute(r.get(), "/grid", "symmetry", nullptr, 0, &count) == BHNSID_READER_ERR_FORMAT);
  // ... and the good ones work.
  CHECK(bhnsid_reader_string_attribute(r.get(), "/", "status", &s) == BHNSID_READER_OK);
  CHECK(std::string(s) == "converged");
  double origin[3] = {0, 0, 0};
  CHECK(bhnsid_reader_numeric_attribute(r.get(), "/grid", "origin_xyz", origin, 3, &count) == BHNSID_READER_OK);
  CHECK(count == 3);
  CHECK(origin[2] == -0.5);
  bhnsid_reader_close(nullptr);  // allowed
}

TEST_CASE("reader.last_error_is_per_thread", "[reader]") {
  CHECK(try_open(work_path("missing_here.h5")).status == BHNSID_READER_ERR_IO);
  std::string other;
  std::thread t([&] {
    other = bhnsid_reader_last_error();  // nothing failed in this thread yet
    bhnsid_reader* r = nullptr;
    bhnsid_reader_open(small_file("older2.h5", "bhnsid-data", 0).c_str(), &r);
  });
  t.join();
  CHECK(other.empty());
  CHECK_THAT(bhnsid_reader_last_error(), Catch::Contains("missing_here.h5"));
}

TEST_CASE("reader.malformed_dataset_is_an_error_at_use", "[reader]") {
  const std::string path = work_path("wrong_shape.h5");
  {
    synth::Writer w(path);
    synth::GridSpec g;
    g.nx = g.ny = g.nz = 6;
    g.dx = 0.2;
    g.origin = {-0.5, -0.5, -0.5};
    w.header(g);
    w.dataset("/ADMBase/alp", {[](double, double, double) { return 1.0; }});
  }
  {  // a dataset of another shape beside it
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hsize_t dims[3] = {2, 3, 4};
    const hid_t sp = H5Screate_simple(3, dims, nullptr);
    const hid_t d = H5Dcreate2(f, "/ADMBase/betax", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    std::vector<double> zeros(24, 0.0);
    H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros.data());
    H5Dclose(d);
    H5Sclose(sp);
    H5Fclose(f);
  }
  const Reader r(path);
  Points p;
  p.add(0, 0, 0);
  const reader_test::Result e = r.try_interpolate({"betax"}, p);
  CHECK(e.status == BHNSID_READER_ERR_FORMAT);
  CHECK_THAT(e.message, Catch::Contains("/ADMBase/betax has shape 2 x 3 x 4"));
  CHECK(r.at("alp", 0, 0, 0) == 1.0);
}
