#pragma once
// A C++ face on the C API for the tests: an owning handle, interpolation into vectors, and the
// status with its message when a call is expected to fail.
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "bhnsid_reader.h"

namespace reader_test {

inline std::string work_path(const std::string& name) { return std::string(READER_TEST_DIR) + "/" + name; }

struct Points {
  std::vector<double> x, y, z;
  void add(double a, double b, double c) {
    x.push_back(a);
    y.push_back(b);
    z.push_back(c);
  }
  std::size_t size() const { return x.size(); }
};

struct Result {
  int status = 0;
  std::string message;
  std::vector<std::vector<double>> values;  // [field][point]
};

class Reader {
 public:
  explicit Reader(const std::string& path) {
    if (bhnsid_reader_open(path.c_str(), &h_) != BHNSID_READER_OK)
      throw std::runtime_error("open " + path + ": " + bhnsid_reader_last_error());
  }
  ~Reader() { bhnsid_reader_close(h_); }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;
  bhnsid_reader* get() const { return h_; }

  Result try_interpolate(const std::vector<std::string>& fields, const Points& p, int order = 4,
                         int outside = BHNSID_READER_OUTSIDE_ERROR) const {
    Result r;
    r.values.assign(fields.size(), std::vector<double>(p.size(), -12345.0));
    std::vector<const char*> names;
    std::vector<double*> out;
    for (std::size_t f = 0; f < fields.size(); ++f) {
      names.push_back(fields[f].c_str());
      out.push_back(r.values[f].data());
    }
    bhnsid_reader_options o;
    bhnsid_reader_default_options(&o);
    o.order = order;
    o.out_of_grid = outside;
    r.status = bhnsid_reader_interpolate(h_, &o, p.size(), p.x.data(), p.y.data(), p.z.data(), fields.size(),
                                         names.data(), out.data());
    if (r.status != BHNSID_READER_OK) r.message = bhnsid_reader_last_error();
    return r;
  }
  /// The values, or an exception with the message.
  std::vector<std::vector<double>> interpolate(const std::vector<std::string>& fields, const Points& p,
                                               int order = 4, int outside = BHNSID_READER_OUTSIDE_ERROR) const {
    Result r = try_interpolate(fields, p, order, outside);
    if (r.status != BHNSID_READER_OK) throw std::runtime_error("interpolate: " + r.message);
    return r.values;
  }
  double at(const std::string& field, double x, double y, double z, int order = 4) const {
    Points p;
    p.add(x, y, z);
    return interpolate({field}, p, order)[0][0];
  }
  double scalar(const std::string& name) const {
    double v = 0;
    if (bhnsid_reader_scalar(h_, name.c_str(), &v) != BHNSID_READER_OK)
      throw std::runtime_error("scalar " + name + ": " + bhnsid_reader_last_error());
    return v;
  }
  bhnsid_reader_grid grid() const {
    bhnsid_reader_grid g;
    bhnsid_reader_grid_info(h_, &g);
    return g;
  }

 private:
  bhnsid_reader* h_ = nullptr;
};

/// Deterministic pseudo-random numbers in [lo, hi) (a test must give the same points every run).
class Random {
 public:
  explicit Random(unsigned long long seed) : s_(seed * 6364136223846793005ULL + 1442695040888963407ULL) {}
  double uniform(double lo, double hi) {
    s_ = s_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(s_ >> 11) * (1.0 / 9007199254740992.0);
  }

 private:
  unsigned long long s_;
};

}  // namespace reader_test
