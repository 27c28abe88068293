#include "manufactured.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bhnsid/core/errors.hpp"
#include "equations.hpp"

namespace bhnsid::mms {

using core::InputError;
using core::TensorKind;

namespace {

ProblemSpec on_grid(ProblemSpec spec, const Grid& grid) {
  spec.half_width = grid.domain().half_width();
  return spec;
}

void check_compatible(const Grid& grid, const ProblemSpec& p, const Vec3& robin_centre) {
  const bool equatorial = grid.symmetry() == Symmetry::equatorial;
  if (p.problem == Problem::poisson && equatorial)
    throw InputError(
        "mms.problem = poisson needs grid.symmetry = none: its exact solution g(tx) g(ty) g(tz), "
        "g(t) = t (1 - t) e^t, is not even in z");
  if (p.problem == Problem::ball) {
    const Vec3& b = p.ball_centre;
    if (equatorial && b[2] != 0)
      throw InputError(fmt::format(
          "mms.ball_centre = ({}, {}, {}) lies off the plane z = 0, which grid.symmetry = equatorial needs", b[0],
          b[1], b[2]));
    const double rc = p.half_width;
    for (double c : b)
      if (!(std::fabs(c) + p.ball_radius < rc))
        throw InputError(fmt::format(
            "mms.ball_radius = {} about mms.ball_centre = ({}, {}, {}) reaches the faces of the cube |x_i| <= {}: "
            "the boundary conditions assume vacuum there",
            p.ball_radius, b[0], b[1], b[2], rc));
    const Vec3& c = robin_centre;
    if (equatorial && c[2] != 0)
      throw InputError(fmt::format(
          "mms.robin_centre = ({}, {}, {}) lies off the plane z = 0, which grid.symmetry = equatorial needs", c[0],
          c[1], c[2]));
    for (double x : c)
      if (!(std::fabs(x) < rc))
        throw InputError(fmt::format("mms.robin_centre = ({}, {}, {}) lies outside the cube |x_i| < {}", c[0], c[1],
                                     c[2], rc));
  }
}

// Exact values and sources at the points of one level. The poisson solution is a product of
// one-dimensional factors, tabulated here per axis: a few multiplications per point instead of
// six exponentials, which matters because the benchmark times setup and analysis with the solve.
class Sampler {
 public:
  Sampler(const ExactSolution& exact, const Level& lv) : exact_(exact), lv_(lv) {
    if (exact.problem() != Problem::poisson) return;
    const PoissonSolution& p = exact.poisson();
    auto tabulate = [&](int count, auto coordinate, std::vector<double>& f, std::vector<double>& f2) {
      for (int i = 0; i < count; ++i) {
        f.push_back(p.factor(coordinate(i)));
        f2.push_back(p.factor_second(coordinate(i)));
      }
    };
    tabulate(lv.nx, [&](int i) { return lv.x(i); }, fx_, fx2_);
    tabulate(lv.ny, [&](int j) { return lv.y(j); }, fy_, fy2_);
    tabulate(lv.nz, [&](int k) { return lv.z(k); }, fz_, fz2_);
  }

  double value(int unknown, int c, int i, int j, int k) const {
    if (fx_.empty()) return exact_.value(unknown, c, Vec3{lv_.x(i), lv_.y(j), lv_.z(k)});
    return at(fx_, i) * at(fy_, j) * at(fz_, k);
  }
  double source(int unknown, int c, int i, int j, int k) const {
    if (fx_.empty()) return exact_.source(unknown, c, Vec3{lv_.x(i), lv_.y(j), lv_.z(k)});
    const double x = at(fx_, i), y = at(fy_, j), z = at(fz_, k);
    return -(at(fx2_, i) * y * z + x * at(fy2_, j) * z + x * y * at(fz2_, k));
  }

 private:
  static double at(const std::vector<double>& v, int i) { return v[static_cast<std::size_t>(i)]; }
  const ExactSolution& exact_;
  const Level& lv_;

 public:
  const Level& level() const { return lv_; }

 private:
  std::vector<double> fx_, fy_, fz_, fx2_, fy2_, fz2_;
};

}  // namespace

Manufactured::Manufactured(Grid& grid, const Settings& settings)
    : grid_(grid), settings_(settings), exact_(on_grid(settings.problem, grid)) {
  settings_.problem = exact_.spec();
  const ProblemSpec& p = settings_.problem;
  check_compatible(grid, p, settings_.robin_centre);

  const bool vector = p.problem == Problem::vector;
  const std::vector<TensorKind> kinds =
      vector ? std::vector<TensorKind>{TensorKind::vector_x, TensorKind::vector_y, TensorKind::vector_z}
             : std::vector<TensorKind>{TensorKind::scalar};
  unknowns_.push_back(vector ? "mms_v" : "mms_u");
  std::vector<std::string> sources{"mms_source"};
  if (p.problem == Problem::coupled) {
    unknowns_.push_back("mms_w");
    sources.push_back("mms_source_w");
  }
  for (std::size_t q = 0; q < unknowns_.size(); ++q) {
    grid.add_field(unknowns_[q], kinds);
    const int s = grid.add_field(sources[q], kinds);
    const int unknown = static_cast<int>(q);
    fill_boxes(s, [&](const Sampler& sample, int c, int i, int j, int k) { return sample.source(unknown, c, i, j, k); });
  }

  std::string mask;
  if (settings_.excision_radius > 0) {
    mask_ = grid.add_mask(mask_name, ExcisionRegion{ExcisionRegion::Shape::sphere, settings_.excision_centre,
                                                    settings_.excision_radius});
    mask = mask_name;
  }

  OuterBoundary dirichlet;
  dirichlet.kind = OuterBoundary::Kind::dirichlet;
  auto spec = [&](std::string name, std::size_t q, OuterBoundary boundary) {
    return EquationSpec{std::move(name), unknowns_[q], sources[q], mask, std::move(boundary)};
  };
  switch (p.problem) {
    case Problem::poisson:
      equations_.push_back(std::make_shared<ScalarEquation>(grid, spec("mms", 0, dirichlet), 0.0));
      break;
    case Problem::nonlinear:
      equations_.push_back(std::make_shared<ScalarEquation>(grid, spec("mms", 0, dirichlet), p.nonlinear_c));
      break;
    case Problem::ball: {
      // The monopole -M/r about the origin satisfies the Robin rows exactly; the ball's offset adds a
      // dipole, whose boundary error falls like 1/r_c^2 (the point of the test).
      OuterBoundary robin;
      robin.kind = OuterBoundary::Kind::robin;
      robin.u_inf = {0.0};
      robin.centre = settings_.robin_centre;
      equations_.push_back(std::make_shared<ScalarEquation>(grid, spec("mms", 0, robin), 0.0));
      break;
    }
    case Problem::vector:
      equations_.push_back(std::make_shared<VectorEquation>(grid, spec("mms", 0, dirichlet), p.vector_coupling));
      break;
    case Problem::coupled:
      equations_.push_back(
          std::make_shared<CoupledEquation>(grid, spec("mms", 0, dirichlet), unknowns_[1], p.coupled_a, 1));
      equations_.push_back(
          std::make_shared<CoupledEquation>(grid, spec("mms_partner", 1, dirichlet), unknowns_[0], p.coupled_b, 3));
      break;
  }
}

template <class Fn>
void Manufactured::fill_boxes(int field, Fn&& value_at) {
  const FieldInfo& info = grid_.field_info(field);
  for (int l = 0; l < grid_.num_boxes(); ++l) {
    const Level& lv = grid_.level(l);
    const Sampler sample(exact_, lv);
    for (int c = 0; c < static_cast<int>(info.components.size()); ++c) {
      double* data = grid_.data(field, c, l);
#pragma omp parallel for schedule(static)
      for (int k = 0; k < lv.nz; ++k)
        for (int j = 0; j < lv.ny; ++j)
          for (int i = 0; i < lv.nx; ++i) data[lv.at(i, j, k)] = value_at(sample, c, i, j, k);
    }
    grid_.fill_ghosts(field, l);
  }
}

void Manufactured::set_initial() {
  const Level& domain = grid_.domain();
  for (std::size_t q = 0; q < unknowns_.size(); ++q) {
    const int field = grid_.field_id(unknowns_[q]);
    const bool dirichlet = equations_[q]->boundary().kind == OuterBoundary::Kind::dirichlet;
    const FieldInfo& info = grid_.field_info(field);
    const int unknown = static_cast<int>(q);
    fill_boxes(field, [&](const Sampler& sample, int c, int i, int j, int k) {
      const Level& lv = sample.level();
      const std::uint8_t* excised = mask_ >= 0 ? grid_.mask(mask_, lv.index) : nullptr;
      // The domain's faces are the outer boundary; an inner box's take the coarser box's values.
      if ((dirichlet && lv.index == domain.index && lv.on_outer_face(i, j, k)) ||
          (excised && excised[lv.at(i, j, k)]))
        return sample.value(unknown, c, i, j, k);
      // A component odd in z vanishes on the symmetry plane; start it there.
      if (lv.z_symmetry && k == 0 && info.parity[static_cast<std::size_t>(c)].z < 0) return 0.0;
      return settings_.initial_guess;
    });
  }
}

void Manufactured::set_exact() {
  for (std::size_t q = 0; q < unknowns_.size(); ++q) {
    const int unknown = static_cast<int>(q);
    fill_boxes(grid_.field_id(unknowns_[q]), [&](const Sampler& sample, int c, int i, int j, int k) {
      return sample.value(unknown, c, i, j, k);
    });
  }
}

Errors Manufactured::errors(int unknown) const {
  const int field = grid_.field_id(unknowns_.at(static_cast<std::size_t>(unknown)));
  const int ncomp = static_cast<int>(grid_.field_info(field).components.size());
  double max = 0, sum2 = 0, volume = 0;
  // The composite grid: each box's points outside the finer box, weighted by the volume a point
  // stands for (dx^3), so that the rms is the L2 norm over the domain.
  for (int l = 0; l < grid_.num_boxes(); ++l) {
    const Level& lv = grid_.level(l);
    const Sampler sample(exact_, lv);
    const double h = l > 0 ? grid_.level(l - 1).half_width() : -1.0, dv = lv.dx * lv.dx * lv.dx;
    auto owned = [&](int i, int j, int k) {
      return l == 0 || std::fmax(std::fabs(lv.x(i)), std::fmax(std::fabs(lv.y(j)), std::fabs(lv.z(k)))) > h * (1 + 1e-12);
    };
    for (int c = 0; c < ncomp; ++c) {
      const double* u = grid_.data(field, c, l);
#pragma omp parallel for schedule(static) reduction(max : max) reduction(+ : sum2, volume)
      for (int k = 0; k < lv.nz; ++k)
        for (int j = 0; j < lv.ny; ++j)
          for (int i = 0; i < lv.nx; ++i) {
            if (!owned(i, j, k)) continue;
            const double e = std::fabs(u[lv.at(i, j, k)] - sample.value(unknown, c, i, j, k));
            // NaN must not hide behind max: it would compare false and leave max unchanged.
            max = std::isnan(e) || e > max ? e : max;
            sum2 += e * e * dv;
            volume += dv;
          }
    }
  }
  Errors out;
  out.max = grid_.global_max(max);
  out.rms = std::sqrt(grid_.global_sum(sum2) / grid_.global_sum(volume));
  return out;
}

std::string Manufactured::line_table() const {
  const bool several = exact_.components() > 1 || unknowns_.size() > 1;
  std::vector<std::vector<std::array<double, 2>>> columns;
  std::vector<std::pair<int, int>> which;  // (unknown, component) per column
  std::string header = "# x";
  for (std::size_t q = 0; q < unknowns_.size(); ++q) {
    const int field = grid_.field_id(unknowns_[q]);
    const int ncomp = static_cast<int>(grid_.field_info(field).components.size());
    for (int c = 0; c < ncomp; ++c) {
      columns.push_back(grid_.line_x(grid_.data(field, c, 0), 0));
      which.emplace_back(static_cast<int>(q), c);
      const std::string base = unknowns_[q].substr(4);  // "mms_u" -> "u"
      const std::string label = ncomp > 1 ? fmt::format("{}_{}", base, "xyz"[c]) : base;
      header += several ? fmt::format("\t{}\texact_{}", label, label) : fmt::format("\t{}\texact", label);
    }
  }
  std::string out = header + "\n";
  for (std::size_t p = 0; p < columns[0].size(); ++p) {
    const double x = columns[0][p][0];
    out += fmt::format("{:.17g}", x);
    for (std::size_t col = 0; col < columns.size(); ++col)
      out += fmt::format("\t{:.17g}\t{:.17g}", columns[col][p][1],
                         exact_.value(which[col].first, which[col].second, Vec3{x, 0.0, 0.0}));
    out += "\n";
  }
  return out;
}

}  // namespace bhnsid::mms
