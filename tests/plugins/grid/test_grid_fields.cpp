// UniformGrid's storage: field registration and allocation, parities from tensor kinds, ghost
// filling on the symmetry plane and excision masks.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/core/errors.hpp"
#include "hierarchy.hpp"
#include "uniform_grid.hpp"

using namespace bhnsid;
using namespace bhnsid::grid;
using core::Storage;
using core::TensorKind;
using core::TimeParity;
using Catch::Matchers::Contains;

namespace {

std::unique_ptr<UniformGrid> make_grid(int n, double dx, Symmetry symmetry) {
  HierarchySpec spec;
  spec.n = n;
  spec.dx = dx;
  spec.symmetry = symmetry;
  return std::make_unique<UniformGrid>(build_hierarchy(spec), symmetry);
}

bool aligned64(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % 64 == 0; }

}  // namespace

TEST_CASE("plugins.grid.fields_are_zeroed_aligned_and_per_level", "[plugins][grid]") {
  // add_field gives every component its own zeroed, 64-byte aligned array of Level::size doubles
  // (the kernels use aligned vector loads) on the levels its storage names: all levels, the finest
  // only, or the coarse ones only; asking for a level that is not stored is a RunFailure. The arrays
  // are zero even when the allocator hands back memory just freed dirty (a first grid's arrays are
  // filled with 7 and freed before the second grid allocates the same sizes); bytes_allocated (the
  // TERMINATE report) counts exactly the arrays handed out.
  for (const Symmetry sym : {Symmetry::none, Symmetry::equatorial}) {
    {
      auto dirty = make_grid(16, 0.25, sym);
      Grid& g = *dirty;
      const int id = g.add_field("w", {TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z});
      for (int c = 0; c < 3; ++c)
        for (int l = 0; l < g.num_levels(); ++l) {
          double* v = g.data(id, c, l);
          for (std::size_t p = 0; p < g.level(l).size; ++p) v[p] = 7;
        }
    }
    auto grid = make_grid(16, 0.25, sym);
    Grid& g = *grid;
    REQUIRE(g.num_levels() == 3);  // 16, 8, 4
    CHECK(grid->bytes_allocated() == 0);
    const int w = g.add_field("w", {TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z});
    const int f = g.add_field("diag", {TensorKind::scalar}, TimeParity::even, Storage::finest_only);
    const int r = g.add_field("rhs", {TensorKind::scalar}, TimeParity::even, Storage::coarse_levels);
    CHECK(w != f);
    CHECK(f != r);
    std::vector<const double*> seen;
    std::size_t expected_bytes = 0;
    auto check_array = [&](const double* v, int l) {
      REQUIRE(v != nullptr);
      CHECK(aligned64(v));
      std::size_t nonzero = 0;
      for (std::size_t p = 0; p < g.level(l).size; ++p) nonzero += v[p] != 0.0;
      CHECK(nonzero == 0);
      for (const double* other : seen) CHECK(other != v);
      seen.push_back(v);
      expected_bytes += g.level(l).size * sizeof(double);
    };
    for (int l = 0; l < g.num_levels(); ++l) {
      INFO("level " << l);
      for (int c = 0; c < 3; ++c) check_array(g.data(w, c, l), l);
      if (l == 0) {
        check_array(g.data(f, 0, l), l);
        CHECK_THROWS_AS(g.data(r, 0, l), core::RunFailure);
      } else {
        check_array(g.data(r, 0, l), l);
        CHECK_THROWS_WITH(g.data(f, 0, l), Contains("diag") && Contains("not stored"));
      }
    }
    CHECK(grid->bytes_allocated() == expected_bytes);
    CHECK_THROWS_AS(g.data(w, 3, 0), core::RunFailure);
    CHECK_THROWS_AS(g.data(w, 0, g.num_levels()), core::RunFailure);
    CHECK_THROWS_AS(g.data(w + 10, 0, 0), core::RunFailure);
    CHECK(g.field_info(w).storage == Storage::all_levels);
    CHECK(g.field_info(f).storage == Storage::finest_only);
    CHECK(g.field_info(w).name == "w");
    CHECK(g.field_info(w).components.size() == 3);
  }
}

TEST_CASE("plugins.grid.field_registration_is_idempotent_and_checked", "[plugins][grid]") {
  // Two plugins may register the same field: the same name, components, time parity and storage
  // return the existing id without new memory; anything different is a RunFailure naming the field,
  // because two equations would otherwise disagree silently about its parity or levels. Lookups of
  // unknown names are RunFailures naming them. References and arrays handed out stay valid while
  // more fields are registered.
  auto grid = make_grid(8, 0.5, Symmetry::equatorial);
  Grid& g = *grid;
  const int beta = g.add_field("beta", {TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z},
                               TimeParity::odd);
  const int chi = g.add_field("chi", {TensorKind::scalar});
  const std::size_t bytes = grid->bytes_allocated();
  CHECK(g.add_field("beta", {TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z}, TimeParity::odd) ==
        beta);
  CHECK(g.add_field("chi", {TensorKind::scalar}) == chi);
  CHECK(grid->bytes_allocated() == bytes);
  CHECK(g.field_id("beta") == beta);
  CHECK(g.field_id("chi") == chi);
  CHECK(g.has_field("chi"));
  CHECK_FALSE(g.has_field("eta"));
  CHECK_THROWS_AS(g.field_id("eta"), core::RunFailure);
  CHECK_THROWS_WITH(g.field_id("eta"), Contains("'eta'"));

  CHECK_THROWS_AS(g.add_field("chi", {TensorKind::vector_x}), core::RunFailure);
  CHECK_THROWS_AS(g.add_field("chi", {TensorKind::scalar, TensorKind::scalar}), core::RunFailure);
  CHECK_THROWS_AS(g.add_field("chi", {TensorKind::scalar}, TimeParity::even, Storage::finest_only), core::RunFailure);
  CHECK_THROWS_WITH(g.add_field("chi", {TensorKind::scalar}, TimeParity::odd), Contains("'chi'"));
  CHECK_THROWS_AS(g.add_field("beta", {TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z}),
                  core::RunFailure);
  CHECK_THROWS_AS(g.add_field("empty", {}), core::RunFailure);
  CHECK_FALSE(g.has_field("empty"));
  CHECK(grid->bytes_allocated() == bytes);

  // field_info returns a reference that callers keep (the multigrid solver holds one across its own
  // add_field calls): it must survive later registrations. Under ASan a dangling one is an error.
  const FieldInfo& info = g.field_info(chi);
  const double* chi_data = g.data(chi, 0, 0);
  for (int m = 0; m < 40; ++m) g.add_field("scratch" + std::to_string(m), {TensorKind::scalar});
  CHECK(info.name == "chi");
  CHECK(info.components == std::vector<TensorKind>{TensorKind::scalar});
  CHECK(g.data(chi, 0, 0) == chi_data);
}

TEST_CASE("plugins.grid.parities_from_tensor_kinds", "[plugins][grid]") {
  // Parities follow physics-notes §8. Under z -> -z: scalars, x and y components of vectors and
  // Ahat^xx, xy, yy, zz are even; vector_z, tensor_xz, tensor_yz are odd. Under y -> -y combined with
  // time reversal: time-even scalars and vector_y flip like the pure reflection (scalar even, W^y
  // of a time-even vector odd); time-odd fields flip once more, so W^y, beta^y, Ahat^xy, Ahat^yz are
  // even and W^x, W^z, Ahat^xx, Ahat^yy, Ahat^zz, Ahat^xz odd.
  auto grid = make_grid(8, 0.5, Symmetry::equatorial);
  Grid& g = *grid;
  const int s = g.add_field("s", {TensorKind::scalar});
  const int v = g.add_field("v", {TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z});
  const int w = g.add_field("w", {TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z}, TimeParity::odd);
  const int a = g.add_field("a",
                            {TensorKind::tensor_xx, TensorKind::tensor_xy, TensorKind::tensor_xz, TensorKind::tensor_yy,
                             TensorKind::tensor_yz, TensorKind::tensor_zz},
                            TimeParity::odd);
  auto z = [&](int field) {
    std::vector<int> p;
    for (const Parity& q : g.field_info(field).parity) p.push_back(q.z);
    return p;
  };
  auto y = [&](int field) {
    std::vector<int> p;
    for (const Parity& q : g.field_info(field).parity) p.push_back(q.y);
    return p;
  };
  CHECK(z(s) == std::vector<int>{1});
  CHECK(y(s) == std::vector<int>{1});
  CHECK(z(v) == std::vector<int>{1, 1, -1});
  CHECK(y(v) == std::vector<int>{1, -1, 1});
  CHECK(z(w) == std::vector<int>{1, 1, -1});
  CHECK(y(w) == std::vector<int>{-1, 1, -1});
  //                               xx  xy  xz  yy  yz  zz
  CHECK(z(a) == std::vector<int>{1, 1, -1, 1, -1, 1});
  CHECK(y(a) == std::vector<int>{-1, 1, -1, -1, 1, -1});
}

TEST_CASE("plugins.grid.fill_ghosts_mirrors_the_symmetry_plane", "[plugins][grid]") {
  // With equatorial symmetry the ghost plane k = -1 (z = -dx) holds the mirror image of k = 1 times
  // the component's z parity, on every level, through both fill_ghosts overloads; no stored point
  // changes. Without symmetry there is no symmetry plane and the array is left exactly as it was.
  // Values are index-coded (1 + i + 100 j + 10^4 k) so a wrong plane or offset cannot pass.
  for (const Symmetry sym : {Symmetry::none, Symmetry::equatorial}) {
    auto grid = make_grid(8, 0.5, sym);
    Grid& g = *grid;
    const int f = g.add_field("f", {TensorKind::scalar, TensorKind::vector_z});
    for (int l = 0; l < g.num_levels(); ++l) {
      const Level& lv = g.level(l);
      INFO("level " << l << (sym == Symmetry::equatorial ? ", equatorial" : ", no symmetry"));
      std::vector<std::vector<double>> before;
      for (int c = 0; c < 2; ++c) {
        double* v = g.data(f, c, l);
        for (std::size_t p = 0; p < lv.size; ++p) v[p] = -999;
        for (int k = 0; k < lv.nz; ++k)
          for (int j = 0; j < lv.ny; ++j)
            for (int i = 0; i < lv.nx; ++i) v[lv.at(i, j, k)] = (c + 1) * (1 + i + 100 * j + 1e4 * k);
        before.emplace_back(v, v + lv.size);
      }
      g.fill_ghosts(f, l);
      // A third array through the raw overload, with an explicit odd parity.
      std::vector<double> raw(before[0]);
      g.fill_ghosts(raw.data(), Parity{-1, 1}, l);
      for (int c = 0; c < 2; ++c) {
        const double* v = g.data(f, c, l);
        const double sign = c == 0 ? 1.0 : -1.0;
        int wrong_stored = 0, wrong_ghost = 0, wrong_raw = 0;
        for (std::size_t p = 0; p < lv.size; ++p) {
          bool on_plane = false;
          for (int j = 0; j < lv.ny && !on_plane; ++j)
            on_plane = lv.z_symmetry && static_cast<std::ptrdiff_t>(p) >= lv.at(0, j, -1) &&
                       static_cast<std::ptrdiff_t>(p) < lv.at(lv.nx, j, -1);
          if (!on_plane) wrong_stored += v[p] != before[static_cast<std::size_t>(c)][p];
        }
        if (lv.z_symmetry)
          for (int j = 0; j < lv.ny; ++j)
            for (int i = 0; i < lv.nx; ++i) {
              wrong_ghost += v[lv.at(i, j, -1)] != sign * v[lv.at(i, j, 1)];
              if (c == 0) wrong_raw += raw[static_cast<std::size_t>(lv.at(i, j, -1))] != -v[lv.at(i, j, 1)];
            }
        else if (c == 0)
          wrong_raw = raw != before[0];
        CHECK(wrong_stored == 0);
        CHECK(wrong_ghost == 0);
        CHECK(wrong_raw == 0);
      }
    }
  }
}

TEST_CASE("plugins.grid.fill_ghost_columns_fills_only_its_columns", "[plugins][grid]") {
  // The shift's box sweeps refresh the mirror plane below their box only: inside the columns
  // (clamped to the level) the ghost holds parity times the image of k = 1, outside it keeps
  // what it held, and no stored point changes. Index-coded values as above.
  auto grid = make_grid(8, 0.5, Symmetry::equatorial);
  Grid& g = *grid;
  const int f = g.add_field("f", {TensorKind::vector_z});
  const Level& lv = g.level(0);
  double* v = g.data(f, 0, 0);
  for (std::size_t p = 0; p < lv.size; ++p) v[p] = -999;
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) v[lv.at(i, j, k)] = 1 + i + 100 * j + 1e4 * k;
  const std::vector<double> before(v, v + lv.size);
  const int i0 = -1, i1 = 3, j0 = 2, j1 = 5;  // i0 off the level: clamped to 0
  g.fill_ghost_columns(f, 0, i0, i1, j0, j1);
  int wrong_inside = 0, wrong_outside = 0, wrong_stored = 0;
  for (int j = 0; j < lv.ny; ++j)
    for (int i = 0; i < lv.nx; ++i) {
      const std::ptrdiff_t ghost = lv.at(i, j, -1);
      if (i <= i1 && j >= j0 && j <= j1)
        wrong_inside += v[ghost] != -v[lv.at(i, j, 1)];
      else
        wrong_outside += v[ghost] != before[static_cast<std::size_t>(ghost)];
      for (int k = 0; k < lv.nz; ++k) wrong_stored += v[lv.at(i, j, k)] != before[static_cast<std::size_t>(lv.at(i, j, k))];
    }
  CHECK(wrong_inside == 0);
  CHECK(wrong_outside == 0);
  CHECK(wrong_stored == 0);
}

namespace {

// Reference membership in integer units of the finest spacing: point (i, j, k) of level l sits at
// 2^l (i - n_l/2, j - n_l/2, k - n_l/2 or k) finest spacings, so the test needs no floating point
// and a point exactly on the surface is unambiguously inside.
struct IntRegion {
  bool cube;
  long cx, cy, cz, half;
  bool contains(long x, long y, long z) const {
    const long dx = std::labs(x - cx), dy = std::labs(y - cy), dz = std::labs(z - cz);
    if (cube) return std::max(dx, std::max(dy, dz)) <= half;
    return dx * dx + dy * dy + dz * dz <= half * half;
  }
};

}  // namespace

TEST_CASE("plugins.grid.masks_cube_and_sphere", "[plugins][grid]") {
  // add_mask marks exactly the stored points with |x - c|_inf <= a (cube) or |x - c|_2 <= a (sphere)
  // on every level, surface points included although dx = 0.1 makes the computed coordinates inexact
  // (the reference is integer arithmetic, see IntRegion); with equatorial symmetry a point is also
  // inside when its mirror image is (the region stands for itself and its image). The sphere's
  // centre lies below z = 0, so on the equatorial grid most of its points come from the image.
  const double dx = 0.1;
  const IntRegion cube{true, 3, -2, 1, 4}, sphere{false, -4, 2, -2, 6};
  auto to_region = [&](const IntRegion& r) {
    ExcisionRegion e;
    e.shape = r.cube ? ExcisionRegion::Shape::cube : ExcisionRegion::Shape::sphere;
    e.centre = {r.cx * dx, r.cy * dx, r.cz * dx};
    e.half_size = r.half * dx;
    return e;
  };
  for (const Symmetry sym : {Symmetry::none, Symmetry::equatorial}) {
    auto grid = make_grid(32, dx, sym);
    Grid& g = *grid;
    REQUIRE(g.num_levels() == 4);  // 32, 16, 8, 4
    const int mc = g.add_mask("bh_cube", to_region(cube));
    const int ms = g.add_mask("bh_sphere", to_region(sphere));
    CHECK(mc != ms);
    CHECK(g.mask_id("bh_cube") == mc);
    CHECK(g.mask_id("bh_sphere") == ms);
    for (const auto& [id, region] : {std::pair{mc, cube}, std::pair{ms, sphere}}) {
      long inside_finest = 0, surface_finest = 0;
      for (int l = 0; l < g.num_levels(); ++l) {
        const Level& lv = g.level(l);
        const std::uint8_t* m = g.mask(id, l);
        REQUIRE(m != nullptr);
        const long s = 1L << l;
        int wrong = 0;
        for (int k = 0; k < lv.nz; ++k)
          for (int j = 0; j < lv.ny; ++j)
            for (int i = 0; i < lv.nx; ++i) {
              const long x = s * (i - lv.n / 2), y = s * (j - lv.n / 2), z = s * (lv.z_symmetry ? k : k - lv.n / 2);
              const bool in = region.contains(x, y, z) || (lv.z_symmetry && region.contains(x, y, -z));
              wrong += m[lv.at(i, j, k)] != (in ? 1 : 0);
              if (l == 0 && in) {
                ++inside_finest;
                const IntRegion shrunk{region.cube, region.cx, region.cy, region.cz, region.half - 1};
                surface_finest += !shrunk.contains(x, y, z) && !(lv.z_symmetry && shrunk.contains(x, y, -z));
              }
            }
        INFO("mask " << id << ", level " << l << (lv.z_symmetry ? ", equatorial" : ""));
        CHECK(wrong == 0);
      }
      // Not vacuous: points inside and points on (or next to) the surface exist on the finest level.
      CHECK(inside_finest > 20);
      CHECK(surface_finest > 4);
    }
    // Same name and region: same mask; same name, other region: RunFailure.
    CHECK(g.add_mask("bh_cube", to_region(cube)) == mc);
    ExcisionRegion other = to_region(cube);
    other.half_size *= 2;
    CHECK_THROWS_WITH(g.add_mask("bh_cube", other), Contains("'bh_cube'"));
    other = to_region(cube);
    other.shape = ExcisionRegion::Shape::sphere;
    CHECK_THROWS_AS(g.add_mask("bh_cube", other), core::RunFailure);
    CHECK_THROWS_AS(g.mask_id("nothing"), core::RunFailure);
    CHECK_THROWS_AS(g.mask(mc, g.num_levels()), core::RunFailure);
    CHECK_THROWS_AS(g.mask(ms + 1, 0), core::RunFailure);
    // A region of no size is a mistake, not an empty mask.
    for (const double bad : {0.0, -0.3, std::numeric_limits<double>::quiet_NaN()}) {
      ExcisionRegion r = to_region(sphere);
      r.half_size = bad;
      CHECK_THROWS_AS(g.add_mask("bad", r), core::RunFailure);
    }
    CHECK_THROWS_AS(g.mask_id("bad"), core::RunFailure);
  }
}
