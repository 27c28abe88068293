// The grid plugin: builds the level hierarchy from the parameters and publishes it as the "grid"
// service before any other plugin's SETUP, so that equations can register their fields there.
#include <fmt/format.h>

#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "hierarchy.hpp"
#include "uniform_grid.hpp"

namespace bhnsid::grid {
namespace {

using core::Bin;
using core::Context;

struct State {
  std::shared_ptr<UniformGrid> grid;
};

class Layout : public GridLayout {
 public:
  Layout(std::vector<Level> levels, const HierarchySpec& spec) : levels_(std::move(levels)), spec_(spec) {}
  const std::vector<Level>& levels() const override { return levels_; }
  std::string describe() const override {
    return fmt::format("grid.n = {} ({}{} levels{})", spec_.n,
                       spec_.boxes > 1 ? fmt::format("{} boxes, ", spec_.boxes) : std::string(), levels_.size(),
                       spec_.symmetry == Symmetry::equatorial ? ", equatorial" : "");
  }

 private:
  std::vector<Level> levels_;
  HierarchySpec spec_;
};

HierarchySpec spec_from(const core::ParamSection& p) {
  HierarchySpec s;
  s.n = static_cast<int>(p.integer("n"));
  s.dx = p.real("dx");
  s.symmetry = p.string("symmetry") == "equatorial" ? Symmetry::equatorial : Symmetry::none;
  s.max_levels = static_cast<int>(p.integer("max_levels"));
  s.min_coarse_intervals = static_cast<int>(p.integer("min_coarse_intervals"));
  s.boxes = static_cast<int>(p.integer("boxes"));
  return s;
}

void declare(core::PluginBuilder& b) {
  auto state = std::make_shared<State>();
  b.implements("grid");
  b.implements(grid_layout_capability);

  b.integer("n")
      .doc("intervals per side of the cube (n + 1 points); even, so that the origin and the axes are grid points")
      .default_value(std::int64_t{64})
      .at_least(2)
      .at_most(4096)
      .refines(core::Refinement::doubles);
  b.real("dx")
      .doc("grid spacing (hatted units); the cube is [-n dx/2, n dx/2]^3")
      .default_value(0.06)
      .greater_than(0)
      .refines(core::Refinement::halves);
  b.keyword("symmetry", {"none", "equatorial"})
      .doc("equatorial: store and compute z >= 0 only, parities from the fields' tensor kinds")
      .default_value(std::string("equatorial"));
  b.integer("max_levels")
      .doc("most levels in the hierarchy, finest included; 0: coarsen by 2 as long as the rule allows")
      .default_value(std::int64_t{0})
      .at_least(0)
      .at_most(64);
  b.integer("min_coarse_intervals")
      .doc("stop coarsening before a level would have fewer intervals per side than this")
      .default_value(std::int64_t{4})
      .at_least(2)
      .at_most(4096);

  b.integer("boxes")
      .doc("nested boxes about the origin, finest included: box b has n intervals of spacing 2^b dx, so the "
           "domain's faces lie at 2^(boxes-1) n dx/2; 1: a single cube")
      .default_value(std::int64_t{1})
      .at_least(1)
      .at_most(16);

  b.schedule(Bin::paramcheck, "check_hierarchy", [](Context& ctx) {
     const HierarchySpec spec = spec_from(ctx.params());
     ctx.publish<GridLayout>(grid_layout_capability, std::make_shared<Layout>(build_hierarchy(spec), spec));
   }).doc("n and the coarsening parameters give a valid hierarchy, published as the layout memory estimates read");
  b.memory([](const Context& ctx, core::MemoryEstimate& m) {
    // The masks: one byte a point on every level, about one per excised region.
    const auto& layout = ctx.services().get<GridLayout>(grid_layout_capability);
    m.add(ctx.plugin(), "masks", fmt::format("excision masks (1 byte a point) at {}", layout.describe()),
          layout.field_bytes(core::Storage::all_levels) / sizeof(double));
  });

  b.schedule(Bin::startup, "create", [state](Context& ctx) {
     const HierarchySpec spec = spec_from(ctx.params());
     auto levels = build_hierarchy(spec);
     for (const Level& lv : levels)
       ctx.log().info("level {}: n = {:4d}, dx = {:.6g}, {} x {} x {} points{}, half width {:.6g}{}", lv.index, lv.n,
                      lv.dx, lv.nx, lv.ny, lv.nz, lv.z_symmetry ? " (z >= 0)" : "", lv.half_width(),
                      lv.inner ? " (inner box)" : "");
     state->grid = std::make_shared<UniformGrid>(std::move(levels), spec.symmetry);
     ctx.publish<Grid>("grid", state->grid);
   }).doc("build the level hierarchy and publish the grid service");

  b.checkpoint([state](Context&, core::CheckpointWriter& out) { state->grid->save(out); },
               [state](Context&, const core::CheckpointReader& in) { state->grid->restore(in); });
  // A neighbour of the same lattice: its fields (and the excision masks the shift restores with
  // them) are the warm start's initial guess; of the next coarser lattice, its fields interpolated.
  b.warm_start([state](Context&, const core::CheckpointReader& in) { state->grid->warm_start(in); });

  b.schedule(Bin::terminate, "report_memory", [state](Context& ctx) {
     if (!state->grid) return;
     ctx.log().info("{:.1f} MiB in grid fields and masks", state->grid->bytes_allocated() / 1048576.0);
     ctx.set_scalar("grid_bytes", static_cast<double>(state->grid->bytes_allocated()));
   }).doc("memory held by fields");
}

}  // namespace
}  // namespace bhnsid::grid

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "grid", "1.0",
                                     "uniform vertex-centred Cartesian grid with a coarsening hierarchy",
                                     &bhnsid::grid::declare};
  return &info;
}
