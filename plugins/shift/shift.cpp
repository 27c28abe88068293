#include "shift.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::shift {

using core::TensorKind;

namespace {

const std::vector<TensorKind> vector{TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z};

/// Calls fn(std::bool_constant<hole>{}, std::bool_constant<matter>{}).
template <class Fn>
void with_kind(bool hole, bool matter, Fn&& fn) {
  if (hole) {
    if (matter)
      fn(std::true_type{}, std::true_type{});
    else
      fn(std::true_type{}, std::false_type{});
  } else {
    if (matter)
      fn(std::false_type{}, std::true_type{});
    else
      fn(std::false_type{}, std::false_type{});
  }
}

/// The fields other plugins register and the shift reads, with the plugin that provides each.
struct Needed {
  const char* name;
  std::size_t components;
  const char* owner;
};
constexpr Needed needed[] = {{fields::chi, 1, "hamiltonian"},
                             {fields::alpha, 1, "implementing 'lapse'"},
                             {fields::ahat, 6, "momentum"}};

const char* puncture_parameters = "puncture.bare_mass, puncture.position, puncture.momentum";

}  // namespace

ShiftEquation::ShiftEquation(Grid& grid, const Lapse* lapse, const Fluid* fluid, const Puncture* puncture, Settings settings)
    : grid_(grid), lapse_(lapse), fluid_(fluid), puncture_(puncture), settings_(settings) {
  if (!lapse_)
    throw core::InputError("shift: no plugin implements 'lapse'; the shift equation reads alpha: add a lapse plugin "
                           "(lapse, lapse_komar) to plugins:");
  for (const Needed& f : needed) {
    if (!grid.has_field(f.name))
      throw core::InputError(fmt::format(
          "shift: the field '{}' is missing; the shift equation reads chi (plugin hamiltonian), alpha "
          "(the plugin implementing 'lapse') and ahat (plugin momentum): add the plugin {}",
          f.name, f.owner));
    const FieldInfo& info = grid.field_info(grid.field_id(f.name));
    if (info.components.size() != f.components || info.storage != core::Storage::all_levels)
      throw core::InputError(fmt::format("shift: the field '{}' has {} component(s) on {}; the shift needs {} on all levels",
                                         f.name, info.components.size(), core::to_string(info.storage), f.components));
  }
  chi_ = grid.field_id(fields::chi);
  ahat_ = grid.field_id(fields::ahat);
  beta_ = grid.add_field(fields::shift, vector, core::TimeParity::odd);
  if (settings_.lattice > 0) {
    const double ratio = settings_.lattice / grid.finest().dx, p = std::round(std::log2(ratio));
    if (!(ratio >= 1 - 1e-9) || std::fabs(ratio - std::exp2(p)) > 1e-9 * ratio)
      throw core::InputError(fmt::format("shift.excision_lattice = {:.9g}: expected dx times a power of 2 (dx = {:.9g} "
                                         "on the finest level: {:.9g}, {:.9g}, ...)",
                                         settings_.lattice, grid.finest().dx, grid.finest().dx, 2 * grid.finest().dx));
    settings_.lattice = grid.finest().dx * std::exp2(p);  // the exact lattice, free of the parameter's rounding
  }
  if (puncture_) {
    check_puncture<core::InputError>(puncture_->bare_mass(), puncture_->position(), puncture_->momentum());
    const Cube cube = excision(puncture_->bare_mass(), puncture_->position());
    // The grid builds the plain cube on every level; update_puncture() rewrites it with the
    // nearest-point rule and whenever the puncture moves.
    mask_ = grid.add_mask(fields::excision_mask, ExcisionRegion{ExcisionRegion::Shape::cube, cube.centre, cube.half});
  }
}

template <class E>
void ShiftEquation::check_puncture(double mass, const std::array<double, 3>& position,
                                   const std::array<double, 3>& momentum) const {
  if (!(mass > 0) || !std::isfinite(mass))
    throw E(fmt::format("shift: the puncture's bare mass Mhat_BH = {} (puncture.bare_mass) must be > 0 for the excision "
                        "cube of side max(Mhat_BH/2, 3 dx)",
                        mass));
  const double v2 = (momentum[0] * momentum[0] + momentum[1] * momentum[1] + momentum[2] * momentum[2]) / (mass * mass);
  if (settings_.excision_value == ExcisionValue::lorentz && !(v2 < 1))
    throw E(fmt::format("shift: |v| = |Phat_BH|/Mhat_BH = {:.6g} (puncture.momentum, puncture.bare_mass) must be < 1 for "
                        "beta_0 = -v/sqrt(1 - v^2) (shift.excision_value = lorentz)",
                        std::sqrt(v2)));
  if (grid_.symmetry() == Symmetry::equatorial && (position[2] != 0 || momentum[2] != 0))
    throw E(fmt::format("shift: with equatorial symmetry the hole must lie in and move along z = 0 (position z = {}, "
                        "momentum z = {}; puncture.position, puncture.momentum)",
                        position[2], momentum[2]));
  const std::string outside = cube_outside_grid(excision(mass, position), grid_.finest());
  if (!outside.empty())
    throw E(fmt::format("shift: {}: move the hole or enlarge the grid ({}; grid.n, grid.dx)", outside,
                        puncture_parameters));
}

Cube ShiftEquation::excision(double mass, const std::array<double, 3>& position) const {
  Cube cube = excision_cube(mass, position, grid_.finest().dx, settings_.min_side);
  if (settings_.lattice > 0) snap_to_lattice(cube, grid_.finest(), settings_.lattice);
  return cube;
}

OuterBoundary ShiftEquation::boundary() const {
  OuterBoundary b;
  b.kind = OuterBoundary::Kind::robin;
  b.u_inf = {0.0, 0.0, 0.0};
  b.centre = {0.0, 0.0, 0.0};
  return b;
}

std::vector<std::string> ShiftEquation::coefficients() const {
  // chi is hamiltonian's unknown and alpha is formed on each level from the lapse's; ahat is filled on every level by its
  // owner and the puncture's terms are computed in the kernel, so none of them is restricted.
  // The projections are formed by the star on each level from its restricted inputs.
  if (!fluid_) return {};
  return fluid_->source_inputs();
}

Sources ShiftEquation::sources(int level) const {
  const Level& lv = grid_.level(level);
  Sources s;
  s.chi = grid_.data(chi_, 0, level);
  s.alpha = lapse_on(grid_, *lapse_, level);
  for (int c = 0; c < 6; ++c) s.ahat[c] = grid_.data(ahat_, c, level);
  if (puncture_) {
    const std::array<double, 3> x_bh = puncture_->position();
    s.half_mass = 0.5 * puncture_->bare_mass();
    s.x0 = lv.x(0) - x_bh[0], s.y0 = lv.y(0) - x_bh[1], s.z0 = lv.z(0) - x_bh[2];
  }
  s.dx = lv.dx;
  if (fluid_) s.matter = matter_sources(grid_, *fluid_, level);
  s.source_scale = settings_.source_scale;
  s.coupling_scale = settings_.coupling_scale;
  s.inv_2h = 0.5 / lv.dx;
  s.sy = lv.sy;
  s.sz = lv.sz;
  return s;
}

void ShiftEquation::residual(const RelaxArgs& args, double* const* out) const {
  const int l = args.level;
  const stencil::ConstComponents v{grid_.data(beta_, 0, l), grid_.data(beta_, 1, l), grid_.data(beta_, 2, l)};
  const stencil::Components o{out[0], out[1], out[2]};
  const Sources s = sources(l);
  with_kind(puncture_ != nullptr, fluid_ != nullptr, [&](auto hole, auto matter) {
    stencil::vector_residual_any(grid_.level(l), v, args.rhs, args.fixed, o,
                                 ShiftLower<decltype(hole)::value, decltype(matter)::value>{s});
  });
}

void ShiftEquation::relax(const RelaxArgs& args) const {
  const int l = args.level;
  const stencil::Components v{grid_.data(beta_, 0, l), grid_.data(beta_, 1, l), grid_.data(beta_, 2, l)};
  const Sources s = sources(l);
  const stencil::Mirror mirror = [this, l] { grid_.fill_ghosts(beta_, l); };
  const int box_sweeps = l < settings_.local_levels ? settings_.local_sweeps : settings_.coarse_local_sweeps;
  const bool local = args.fixed && box_sweeps > 0 && static_cast<std::size_t>(l) < held_box_.size();
  with_kind(puncture_ != nullptr, fluid_ != nullptr, [&](auto hole, auto matter) {
    const ShiftLower<decltype(hole)::value, decltype(matter)::value> lower{s};
    stencil::vector_relax_any(grid_.level(l), v, args.rhs, args.fixed, args.omega, mirror, lower);
    if (local) {
      // The same sweep on the box about the hole (a few thousand points), box_sweeps times.
      // It reads the mirror plane only below the box and one column around it; the solver
      // refreshes the whole plane after relax.
      const Level& lv = grid_.level(l);
      const stencil::Box& box = held_box_[static_cast<std::size_t>(l)];
      const bool touches_ghost = lv.z_symmetry && box.k0 == lv.k_begin();
      const stencil::Mirror box_mirror = [this, l, &box] {
        grid_.fill_ghost_columns(beta_, l, box.i0 - 1, box.i1 + 1, box.j0 - 1, box.j1 + 1);
      };
      if (touches_ghost) box_mirror();
      for (int sweep = 0; sweep < box_sweeps; ++sweep) {
        stencil::vector_relax_any(lv, v, args.rhs, args.fixed, args.omega, box_mirror, lower, box);
        if (touches_ghost) box_mirror();
      }
    }
  });
}

ExcisionReport ShiftEquation::update_puncture() {
  ExcisionReport report;
  if (!puncture_) return report;
  const double mass = puncture_->bare_mass();
  const std::array<double, 3> position = puncture_->position(), momentum = puncture_->momentum();
  check_puncture<core::RunFailure>(mass, position, momentum);
  report.cube = excision(mass, position);
  report.beta0 = excision_shift(momentum, mass, settings_.excision_value);
  const int coarsest = grid_.num_levels() - 1;
  if (!built_ || mass != last_mass_ || position != last_position_) {
    report.changed = true;
    for (int l = 0; l <= coarsest; ++l) {
      const Level& lv = grid_.level(l);
      // The grid builds a mask once from its region; this cube moves with the hole and holds the
      // nearest point of a level it misses, so the bytes are rewritten here (Grid::mask_data).
      // The multigrid reads the mask through Grid::mask at every solve and sees the new points.
      std::uint8_t* bytes = grid_.mask_data(mask_, l);
      std::vector<std::uint8_t> before;
      if (l == coarsest && built_) before.assign(bytes, bytes + lv.size);
      bool nearest = false;
      const int count = build_mask(lv, report.cube, bytes, nearest);
      if (nearest) report.nearest_levels.push_back(l);
      if (l == 0) report.finest_points = count;
      if (l == coarsest && built_) report.coarsest_changed = !std::equal(before.begin(), before.end(), bytes);
    }
    held_box_.assign(static_cast<std::size_t>(coarsest + 1), {});
    for (int l = 0; l <= coarsest; ++l) {
      const Level& lv = grid_.level(l);
      const std::uint8_t* m = grid_.mask(mask_, l);
      stencil::Box b{lv.nx, -1, lv.ny, -1, lv.nz, -1};
      for (int k = lv.k_begin(); k < lv.nz - 1; ++k)
        for (int j = 1; j < lv.ny - 1; ++j)
          for (int i = 1; i < lv.nx - 1; ++i)
            if (m[lv.at(i, j, k)]) {
              b.i0 = std::min(b.i0, i), b.i1 = std::max(b.i1, i), b.j0 = std::min(b.j0, j);
              b.j1 = std::max(b.j1, j), b.k0 = std::min(b.k0, k), b.k1 = std::max(b.k1, k);
            }
      const int w = settings_.local_width;
      b.i0 = std::max(b.i0 - w, 1), b.i1 = std::min(b.i1 + w, lv.nx - 2);
      b.j0 = std::max(b.j0 - w, 1), b.j1 = std::min(b.j1 + w, lv.ny - 2);
      b.k0 = std::max(b.k0 - w, lv.k_begin()), b.k1 = std::min(b.k1 + w, lv.nz - 2);
      held_box_[static_cast<std::size_t>(l)] = b;
    }
    last_mass_ = mass;
    last_position_ = position;
    last_finest_points_ = report.finest_points;
    last_nearest_levels_ = report.nearest_levels;
  } else {
    report.finest_points = last_finest_points_;
    report.nearest_levels = last_nearest_levels_;
  }
  built_ = true;
  // beta = beta_0 at every excised point of every level. The multigrid injects the finest level's
  // values into the coarse levels before each solve, so the finest level's are the ones that count.
  for (int l = 0; l <= coarsest; ++l) {
    const Level& lv = grid_.level(l);
    const std::uint8_t* m = grid_.mask(mask_, l);
    double* b[3] = {grid_.data(beta_, 0, l), grid_.data(beta_, 1, l), grid_.data(beta_, 2, l)};
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j)
        for (int i = 0; i < lv.nx; ++i) {
          const std::ptrdiff_t p = lv.at(i, j, k);
          if (!m[p]) continue;
          for (int c = 0; c < 3; ++c) b[c][p] = report.beta0[static_cast<std::size_t>(c)];
        }
    grid_.fill_ghosts(beta_, l);
  }
  return report;
}

}  // namespace bhnsid::shift
