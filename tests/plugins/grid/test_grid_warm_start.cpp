// UniformGrid::warm_start: from a checkpoint of the same lattice every array comes back as it was;
// from the next coarser lattice of the same cube each field's finest level is the trilinear
// interpolation of the coarse run's finest level (exact where the points coincide and for linear
// data, second order between them) and the coarse run's level l is this grid's level l + 1; any
// other lattice is an InputError. The checkpoint is an in-memory stand-in for the core's file.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bhnsid/core/errors.hpp"
#include "hierarchy.hpp"
#include "uniform_grid.hpp"

using namespace bhnsid;
using namespace bhnsid::grid;
using core::TensorKind;
using Catch::Matchers::Contains;

namespace {

// One plugin section of a checkpoint, held in memory: what the writer records the reader returns.
class MemoryCheckpoint final : public core::CheckpointWriter, public core::CheckpointReader {
 public:
  bool has(const std::string& name) const override { return entries_.count(name) != 0; }

 protected:
  void record(const std::string& name, char type, const void* data, std::size_t bytes) override {
    const char* p = static_cast<const char*>(data);
    entries_[name] = {type, std::vector<char>(p, p + bytes)};
  }
  std::size_t size(const std::string& name, char type) const override { return entry(name, type).size(); }
  void read(const std::string& name, char type, void* out, std::size_t bytes) const override {
    const std::vector<char>& e = entry(name, type);
    if (e.size() != bytes) throw core::InputError("checkpoint entry " + name + ": another size");
    std::memcpy(out, e.data(), bytes);
  }

 private:
  const std::vector<char>& entry(const std::string& name, char type) const {
    auto it = entries_.find(name);
    if (it == entries_.end() || it->second.first != type) throw core::InputError("checkpoint entry " + name + ": missing");
    return it->second.second;
  }
  std::map<std::string, std::pair<char, std::vector<char>>> entries_;
};

std::unique_ptr<UniformGrid> make_grid(int n, double dx) {
  HierarchySpec spec;
  spec.n = n;
  spec.dx = dx;
  spec.symmetry = Symmetry::equatorial;
  return std::make_unique<UniformGrid>(build_hierarchy(spec), Symmetry::equatorial);
}

int add_u(Grid& g) { return g.add_field("u", {TensorKind::scalar}); }

// Even in z, as a scalar under equatorial symmetry must be: linear in x and y, quadratic in z.
double profile(double x, double y, double z) { return 1 + 0.5 * x - 2 * y + 3 * z * z; }

void fill(Grid& g, int field, int level) {
  const Level& lv = g.level(level);
  double* v = g.data(field, 0, level);
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) v[lv.at(i, j, k)] = profile(lv.x(i), lv.y(j), lv.z(k)) + level;
  g.fill_ghosts(field, level);
}

// A grid of u = profile on every level, saved: what a converged run of that lattice leaves.
std::unique_ptr<UniformGrid> saved_grid(int n, double dx, MemoryCheckpoint& checkpoint, int& field) {
  auto g = make_grid(n, dx);
  field = add_u(*g);
  for (int l = 0; l < g->num_levels(); ++l) fill(*g, field, l);
  g->save(checkpoint);
  return g;
}

}  // namespace

TEST_CASE("plugins.grid.warm_start_interpolates_the_next_coarser_lattice", "[plugins][grid][warm]") {
  MemoryCheckpoint checkpoint;
  int cf = 0;
  auto coarse = saved_grid(16, 0.2, checkpoint, cf);

  auto fine = make_grid(32, 0.1);
  const int ff = add_u(*fine);
  REQUIRE(fine->num_levels() == coarse->num_levels() + 1);
  fine->warm_start(checkpoint);

  const Level& lv = fine->level(0);
  const double* u = fine->data(ff, 0, 0);
  double worst_shared = 0, worst_between = 0;
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const double error = std::fabs(u[lv.at(i, j, k)] - profile(lv.x(i), lv.y(j), lv.z(k)));
        (k % 2 == 0 ? worst_shared : worst_between) = std::fmax(k % 2 == 0 ? worst_shared : worst_between, error);
      }
  // Linear in x, y: exact; z^2 between two coarse points off by f'' H^2 / 8 = 6 (0.2)^2 / 8.
  CHECK(worst_shared < 1e-13);
  CHECK(worst_between == Approx(6 * 0.2 * 0.2 / 8).epsilon(1e-9));
  // The ghost below the symmetry plane mirrors k = 1.
  CHECK(u[lv.at(3, 4, -1)] == u[lv.at(3, 4, 1)]);
  // The coarse run's level l is the fine grid's level l + 1, as it was.
  for (int l = 1; l < fine->num_levels(); ++l) {
    const Level& cl = fine->level(l);
    const double* v = fine->data(ff, 0, l);
    const double* w = coarse->data(cf, 0, l - 1);
    REQUIRE(cl.size == coarse->level(l - 1).size);
    for (std::size_t p = 0; p < cl.size; ++p) REQUIRE(v[p] == w[p]);
  }
}

TEST_CASE("plugins.grid.warm_start_of_the_same_lattice_restores_and_of_another_refuses", "[plugins][grid][warm]") {
  MemoryCheckpoint checkpoint;
  int sf = 0;
  auto source = saved_grid(16, 0.2, checkpoint, sf);

  auto same = make_grid(16, 0.2);
  const int id = add_u(*same);
  same->warm_start(checkpoint);
  for (int l = 0; l < same->num_levels(); ++l)
    for (std::size_t p = 0; p < same->level(l).size; ++p) REQUIRE(same->data(id, 0, l)[p] == source->data(sf, 0, l)[p]);

  // Two refinements away, and a coarser grid than the checkpoint's.
  for (const auto& [n, dx] : {std::pair{64, 0.05}, std::pair{8, 0.4}}) {
    auto other = make_grid(n, dx);
    add_u(*other);
    CHECK_THROWS_WITH(other->warm_start(checkpoint), Contains("neither this run's") && Contains("nor the next coarser"));
  }
}
