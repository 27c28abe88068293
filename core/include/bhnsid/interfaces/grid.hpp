#pragma once
// The grid interface, published by a grid plugin under the capability "grid". Every equation and
// the multigrid solver reach grid data through it: the level hierarchy, named fields stored as
// plain contiguous arrays, ghost filling, excision masks and global reductions. Halo exchange and
// every reduction live here so that a domain-decomposed (MPI) grid can replace the serial one
// without touching an equation plugin.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/memory.hpp"
#include "bhnsid/core/services.hpp"
#include "bhnsid/core/variables.hpp"

namespace bhnsid {

enum class Symmetry { none, equatorial };

/// Sign of one field component under the grid's reflections: z -> -z (always used with equatorial
/// symmetry) and y -> -y combined with time reversal (reserved for a quadrant grid, physics-notes §8).
struct Parity {
  int z = 1;
  int y = 1;
};

/// Geometry and memory layout of one level. Stored point (i, j, k), 0 <= i < nx, 0 <= j < ny,
/// 0 <= k < nz, sits at origin + dx (i, j, k) and lives at data[at(i, j, k)]. One ghost layer
/// surrounds the stored points; only ghosts on symmetry planes carry values (fill_ghosts).
struct Level {
  int index = 0;  ///< 0 is the finest level
  int n = 0;      ///< intervals per side of the full cube; the cube is [-n dx/2, n dx/2]^3
  int nx = 0, ny = 0, nz = 0;
  double dx = 0;
  std::array<double, 3> origin{};  ///< coordinates of stored point (0, 0, 0)
  bool z_symmetry = false;          ///< k = 0 is the plane z = 0 and ghost k = -1 mirrors k = 1
  std::ptrdiff_t sy = 0, sz = 0;    ///< strides in y and z (x is contiguous)
  std::ptrdiff_t offset = 0;        ///< array index of stored point (0, 0, 0)
  std::size_t size = 0;             ///< doubles per array, ghosts included
  /// A box inside the next coarser level (grid.boxes > 1), which covers twice its extent: its faces
  /// are not the domain's boundary but take that level's values.
  bool inner = false;

  std::ptrdiff_t at(int i, int j, int k) const { return offset + i + sy * j + sz * k; }
  double x(int i) const { return origin[0] + dx * i; }
  double y(int j) const { return origin[1] + dx * j; }
  double z(int k) const { return origin[2] + dx * k; }
  /// Points whose equation is the full interior stencil: i, j in [1, nx-2], k in [k_begin(), nz-2].
  /// All other stored points lie on an outer face of the cube and carry boundary rows.
  int k_begin() const { return z_symmetry ? 0 : 1; }
  bool on_outer_face(int i, int j, int k) const {
    return i == 0 || i == nx - 1 || j == 0 || j == ny - 1 || k == nz - 1 || (k == 0 && !z_symmetry);
  }
  /// Half-width of the cube, r_c = n dx / 2.
  double half_width() const { return 0.5 * n * dx; }
  /// The stored indices along `axis` (0, 1, 2) whose coordinate may lie in [lo, hi], one index of
  /// slack each way, clamped to the level: [first, last], empty when first > last. Loops over a
  /// small region (an excision cube) visit these instead of the whole level and test exactly.
  std::array<int, 2> indices_near(int axis, double lo, double hi) const {
    const std::size_t a = static_cast<std::size_t>(axis);
    const int extent = axis == 0 ? nx : axis == 1 ? ny : nz;
    const double first = std::floor((lo - origin[a]) / dx) - 1, last = std::ceil((hi - origin[a]) / dx) + 1;
    return {static_cast<int>(std::clamp(first, 0.0, static_cast<double>(extent))),
            static_cast<int>(std::clamp(last, -1.0, extent - 1.0))};
  }
  /// indices_near along each axis for the box [lo, hi]; under equatorial symmetry the z range also
  /// covers the box's mirror image, for a region there stands for itself and its image.
  std::array<std::array<int, 2>, 3> indices_near_box(const std::array<double, 3>& lo,
                                                     const std::array<double, 3>& hi) const {
    const double zlo = z_symmetry ? std::fmin(lo[2], -hi[2]) : lo[2];
    const double zhi = z_symmetry ? std::fmax(hi[2], -lo[2]) : hi[2];
    return {indices_near(0, lo[0], hi[0]), indices_near(1, lo[1], hi[1]), indices_near(2, zlo, zhi)};
  }
  /// Distance from p to the nearest stored point (the puncture's 1/r needs it off the points).
  double distance_to_nearest_point(const std::array<double, 3>& p) const {
    const int extent[3] = {nx, ny, nz};
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const std::size_t s = static_cast<std::size_t>(a);
      const double t = std::clamp(std::round((p[s] - origin[s]) / dx), 0.0, extent[a] - 1.0);
      const double d = p[s] - (origin[s] + t * dx);
      d2 += d * d;
    }
    return std::sqrt(d2);
  }
};

/// The part of `coarse` that `fine` covers, in coarse's spacing and memory layout: its point
/// (I, J, K) is the coarse point at fine's point (2I, 2J, 2K). Where both levels cover one cube it
/// is `coarse` itself, so a transfer between a box and the coarser box about it is the same code
/// as one between a level and its coarsening.
inline Level covered_part(const Level& coarse, const Level& fine) {
  Level part = coarse;
  std::ptrdiff_t shift[3];
  for (std::size_t a = 0; a < 3; ++a)
    shift[a] = static_cast<std::ptrdiff_t>(std::lround((fine.origin[a] - coarse.origin[a]) / coarse.dx));
  part.n = fine.n / 2;
  part.nx = (fine.nx - 1) / 2 + 1;
  part.ny = (fine.ny - 1) / 2 + 1;
  part.nz = (fine.nz - 1) / 2 + 1;
  part.origin = fine.origin;
  part.offset = coarse.offset + shift[0] + coarse.sy * shift[1] + coarse.sz * shift[2];
  return part;
}

/// Calls fn(p, x, y) for the array index p and the coordinates of every stored point of a level
/// (ghosts excluded), OpenMP over planes and each row an omp simd loop: for pointwise densities and
/// fills, where fn is an inlinable lambda without branches (selects vectorise, branches do not).
template <class Fn>
inline void for_stored_points_xy(const Level& lv, Fn&& fn) {
#pragma omp parallel for schedule(static)
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j) {
      const std::ptrdiff_t p0 = lv.at(0, j, k);
      const double y = lv.y(j), x0 = lv.x(0), h = lv.dx;
#pragma omp simd
      for (int i = 0; i < lv.nx; ++i) fn(p0 + i, x0 + h * i, y);
    }
}

/// The same without the coordinates: fn(p).
template <class Fn>
inline void for_stored_points(const Level& lv, Fn&& fn) {
  for_stored_points_xy(lv, [&](std::ptrdiff_t p, double, double) { fn(p); });
}

struct FieldInfo {
  std::string name;
  std::vector<core::TensorKind> components;  ///< one entry per component (1 or 3 for equations)
  std::vector<Parity> parity;                ///< derived from the tensor kinds and the time parity
  core::Storage storage = core::Storage::all_levels;
};

/// A region whose points are held at Dirichlet values (black-hole excision). A point is inside when
/// |x - centre|_inf <= half_size (cube) or |x - centre|_2 <= half_size (sphere).
struct ExcisionRegion {
  enum class Shape { cube, sphere } shape = Shape::cube;
  std::array<double, 3> centre{};
  double half_size = 0;
};

class Grid : public core::Service {
 public:
  /// Defined in the core library: its type information then exists once, there, and
  /// dynamic_cast from Service works across plugins loaded with RTLD_LOCAL on any C++ runtime.
  ~Grid() override;
  virtual Symmetry symmetry() const = 0;
  virtual int num_levels() const = 0;
  virtual const Level& level(int index) const = 0;
  const Level& finest() const { return level(0); }
  const Level& coarsest() const { return level(num_levels() - 1); }
  /// Nested boxes: levels 0 .. num_boxes() - 1 are boxes of one spacing each, each inside the next;
  /// the outermost box's faces are the domain's boundary. 1 for a single cube.
  int num_boxes() const {
    int boxes = 1;
    while (boxes < num_levels() && level(boxes - 1).inner) ++boxes;
    return boxes;
  }
  /// The outermost box: the domain (its faces carry the outer boundary conditions).
  const Level& domain() const { return level(num_boxes() - 1); }

  /// Registers and allocates (zeroed) a field with one component per tensor kind; registering the
  /// same name again with the same components returns the existing id, a conflicting one throws.
  virtual int add_field(const std::string& name, const std::vector<core::TensorKind>& components,
                        core::TimeParity time_parity = core::TimeParity::even,
                        core::Storage storage = core::Storage::all_levels) = 0;
  /// The id of a registered field; throws core::RunFailure naming the field when there is none.
  virtual int field_id(const std::string& name) const = 0;
  virtual bool has_field(const std::string& name) const = 0;
  virtual const FieldInfo& field_info(int field) const = 0;
  /// Registered fields: their ids are 0 .. num_fields() - 1, in the order of registration.
  virtual int num_fields() const = 0;
  /// The array of one component on one level (Level::size doubles, 64-byte aligned).
  virtual double* data(int field, int component, int level) = 0;
  virtual const double* data(int field, int component, int level) const = 0;

  /// Fills the ghost points of one array from its stored points: mirror images across symmetry
  /// planes (times the parity), and, in a decomposed grid, the neighbours' points.
  virtual void fill_ghosts(double* values, Parity parity, int level) const = 0;
  void fill_ghosts(int field, int level) {
    const FieldInfo& info = field_info(field);
    for (int c = 0; c < static_cast<int>(info.components.size()); ++c)
      fill_ghosts(data(field, c, level), info.parity[c], level);
  }
  /// fill_ghosts for the columns i0 <= i <= i1, j0 <= j <= j1 only (clamped to the level): what a
  /// sweep confined to a box about the hole reads. The shift refreshes the mirror plane twice per
  /// sweep of its box, 32 times per relaxation: the whole plane each time cost about 1 % of a run.
  /// The default fills every column.
  virtual void fill_ghost_columns(double* values, Parity parity, int level, int i0, int i1, int j0, int j1) const {
    (void)i0, (void)i1, (void)j0, (void)j1;
    fill_ghosts(values, parity, level);
  }
  void fill_ghost_columns(int field, int level, int i0, int i1, int j0, int j1) {
    const FieldInfo& info = field_info(field);
    for (int c = 0; c < static_cast<int>(info.components.size()); ++c)
      fill_ghost_columns(data(field, c, level), info.parity[c], level, i0, i1, j0, j1);
  }

  /// Registers an excision mask (1 inside the region, 0 outside) built on every level; the same
  /// name again with the same region returns the existing id.
  virtual int add_mask(const std::string& name, const ExcisionRegion& region) = 0;
  virtual int mask_id(const std::string& name) const = 0;
  virtual const std::uint8_t* mask(int mask, int level) const = 0;
  /// The same bytes, writable, for the plugin that owns a region which moves between solves (the
  /// shift's excision cube follows the black hole, and holds the nearest point on a level the cube
  /// misses). The solver reads masks afresh at every solve.
  virtual std::uint8_t* mask_data(int mask, int level) = 0;

  /// Reductions of per-process partial results over all processes (identity in a serial grid).
  virtual double global_sum(double local) const = 0;
  virtual double global_max(double local) const = 0;

  /// Second-order volume integral over the whole cube (both halves with equatorial symmetry) of
  /// one component on one level: trapezoidal weights, the symmetry plane counted once.
  virtual double integrate(const double* values, Parity parity, int level) const = 0;
  /// Value at an arbitrary point of the cube on one level: 4-point Lagrange interpolation along
  /// each axis (tricubic), using symmetry images near the z = 0 plane and one-sided stencils at faces.
  virtual double interpolate(const double* values, Parity parity, int level, std::array<double, 3> point) const = 0;
  /// The stored values on the x axis (j at y = 0, k at z = 0): pairs (x_i, value).
  virtual std::vector<std::array<double, 2>> line_x(const double* values, int level) const = 0;
};

/// For a plugin that reads the finest level as the whole domain: refuses nested boxes with one
/// input error naming the parameter.
inline void require_single_box(const Grid& grid, const std::string& plugin) {
  if (grid.num_boxes() > 1)
    throw core::InputError(fmt::format(
        "grid.boxes = {}: the plugin '{}' works on a single cube only (grid.boxes = 1)", grid.num_boxes(), plugin));
}

/// A grid field's name and number of components, for memory estimates.
struct FieldSize {
  const char* name;
  int components;
};

/// The hierarchy a grid will build, published under the capability "grid_layout" during PARAMCHECK,
/// before anything is allocated, so that every plugin can estimate its memory from parameters
/// alone (PluginBuilder::memory).
class GridLayout : public core::Service {
 public:
  ~GridLayout() override;
  /// The levels, finest first, exactly as the grid will build them.
  virtual const std::vector<Level>& levels() const = 0;
  /// The parameters that set the sizes, for messages, e.g. "grid.n = 128, 6 levels".
  virtual std::string describe() const = 0;

  /// Bytes of one field component stored with `storage`, ghosts included.
  double field_bytes(core::Storage storage) const {
    const std::vector<Level>& lv = levels();
    const std::size_t first = storage == core::Storage::coarse_levels ? 1 : 0;
    const std::size_t count = storage == core::Storage::finest_only ? 1 : lv.size();
    double bytes = 0;
    for (std::size_t l = first; l < count; ++l) bytes += static_cast<double>(lv[l].size) * sizeof(double);
    return bytes;
  }
  /// Adds a grid field of `components` components to an estimate, counted once per name as the grid
  /// stores it once however many plugins register it.
  void estimate_field(core::MemoryEstimate& estimate, const std::string& plugin, const std::string& name,
                      int components, core::Storage storage = core::Storage::all_levels) const {
    estimate.add(plugin, "field " + name,
                 fmt::format("field {} ({} component{}, {}) at {}", name, components, components == 1 ? "" : "s",
                             core::to_string(storage), describe()),
                 components * field_bytes(storage));
  }
  template <class Sizes>
  void estimate_fields(core::MemoryEstimate& estimate, const std::string& plugin, const Sizes& sizes) const {
    for (const FieldSize& f : sizes) estimate_field(estimate, plugin, f.name, f.components);
  }
};

/// The capability a grid's layout is published under, and the counts the memory estimate shares.
inline constexpr const char* grid_layout_capability = "grid_layout";

}  // namespace bhnsid
