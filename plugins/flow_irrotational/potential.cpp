#include "potential.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseLU>
#include <Eigen/SparseCore>
#include <unsupported/Eigen/IterativeSolvers>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "bhnsid/core/errors.hpp"

namespace bhnsid::flow_irrotational {

double face_average_rho0(const Eos& eos, double s_f, double g1, double g2, double dx, int samples) {
  const double w = 0.5 * dx * (std::fabs(g1) + std::fabs(g2));
  if (s_f + w <= 0) return 0.0;
  // Deep inside, the midpoint rule; where the surface cuts the face, sub-squares (rho0 is zero on
  // part of it and not smooth across the cut); in between, within one face's range of s of the
  // cut, a blend of the two. Without the blend the average jumps as a corner crosses the surface
  // wherever rho0(h) is not linear (for SLy's crust, rho0 ~ s^2.9, the midpoint rule is 40 % off
  // there): the outer iteration then cycled about the jump (period 6, star change 5e-4). A
  // Gamma = 2 polytrope's rho0 is linear in s, and both rules agree on uncut faces.
  const double mid = eos.rho0_from_enthalpy(1.0 + s_f);
  const double t = w > 0 ? (s_f - w) / (2 * w) : 1.0;
  if (t >= 1) return mid;
  double sum = 0;
  const double h = dx / samples;
  for (int a = 0; a < samples; ++a)
    for (int b = 0; b < samples; ++b) {
      const double s = s_f + g1 * (-0.5 * dx + (a + 0.5) * h) + g2 * (-0.5 * dx + (b + 0.5) * h);
      if (s > 0) sum += eos.rho0_from_enthalpy(1.0 + s);
    }
  const double sub = sum / (samples * samples);
  return t <= 0 ? sub : t * mid + (1 - t) * sub;
}

namespace {

using Index = std::ptrdiff_t;

/// The finest level with the z = 0 mirror: reads at k = -1 go to the ghost layer (filled), and the
/// unknown of a mirror point is that of its image (Psitilde is even in z).
struct Lattice {
  const Level& lv;
  Index at(int i, int j, int k) const { return lv.at(i, j, k); }
  Index image(int i, int j, int k) const { return lv.at(i, j, lv.z_symmetry ? std::abs(k) : k); }
};

constexpr int unit[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

/// A face from vertex L to L + e_d, with the flux through it F = const + sum coef * Psi(col).
struct FaceFlux {
  double a = 0;                 ///< the face coefficient a_f (0: no flux)
  double constant = 0;          ///< -a phi^4 beta^d (the shift's part of -a phi^4 B^d)
  double constant_xi = 0;       ///< -a phi^4 xi^d (the rotation's part, per unit Omegahat)
  std::vector<std::pair<Index, double>> terms;
};

class Operator {
 public:
  Operator(const Level& lv, const Eos& eos, const PotentialCoefficients& c, const PotentialSettings& s)
      : lat_{lv}, eos_(eos), c_(c), settings_(s) {}

  double s_at(int i, int j, int k) const { return c_.level_set[lat_.at(i, j, k)]; }
  bool in_box(int i, int j, int k) const {
    return i >= c_.box[0][0] && i <= c_.box[0][1] && j >= c_.box[1][0] && j <= c_.box[1][1] && std::abs(k) <= c_.box[2][1] &&
           (lat_.lv.z_symmetry || k >= c_.box[2][0]);
  }

  /// a_f of the face from (i, j, k) along d: the face average of rho0 times the mean of phi^2/(alpha h).
  double coefficient(int i, int j, int k, int d) const {
    const int i1 = i + unit[d][0], j1 = j + unit[d][1], k1 = k + unit[d][2];
    if (!in_box(i, j, k) || !in_box(i1, j1, k1)) return 0.0;
    const double s0 = s_at(i, j, k), s1 = s_at(i1, j1, k1);
    const double s_f = 0.5 * (s0 + s1);
    const double dx = lat_.lv.dx;
    double g[2];
    int n = 0;
    for (int t = 0; t < 3; ++t) {
      if (t == d) continue;
      const int ti = unit[t][0], tj = unit[t][1], tk = unit[t][2];
      if (!in_box(i + ti, j + tj, k + tk) || !in_box(i - ti, j - tj, k - tk) || !in_box(i1 + ti, j1 + tj, k1 + tk) ||
          !in_box(i1 - ti, j1 - tj, k1 - tk)) {
        g[n++] = 0.0;
        continue;
      }
      g[n++] = (s_at(i + ti, j + tj, k + tk) - s_at(i - ti, j - tj, k - tk) + s_at(i1 + ti, j1 + tj, k1 + tk) -
                s_at(i1 - ti, j1 - tj, k1 - tk)) /
               (4 * dx);
    }
    const double rho = face_average_rho0(eos_, s_f, g[0], g[1], dx, settings_.face_samples);
    if (!(rho > 0)) return 0.0;
    auto weight = [&](Index p) {
      const double ph = c_.phi[p], h = std::max(1.0 + c_.level_set[p], 1.0);
      return ph * ph / (c_.alpha[p] * h);
    };
    return rho * 0.5 * (weight(lat_.at(i, j, k)) + weight(lat_.at(i1, j1, k1)));
  }

  /// Marks the physical vertices (a face with a > 0) and stores each face's a_f.
  void classify() {
    const Level& lv = lat_.lv;
    physical_.assign(lv.size, 0);
    for (int d = 0; d < 3; ++d) face_a_[d].assign(lv.size, 0.0);
    for (int k = c_.box[2][0]; k <= c_.box[2][1]; ++k)
      for (int j = c_.box[1][0]; j <= c_.box[1][1]; ++j)
        for (int i = c_.box[0][0]; i <= c_.box[0][1]; ++i)
          for (int d = 0; d < 3; ++d) {
            const double a = coefficient(i, j, k, d);
            if (!(a > 0)) continue;
            face_a_[d][lat_.at(i, j, k)] = a;
            physical_[lat_.image(i, j, k)] = 1;
            physical_[lat_.image(i + unit[d][0], j + unit[d][1], k + unit[d][2])] = 1;
          }
    // The face from k = -1 to k = 0 is the image of the face from 0 to 1.
  }

  /// Closes every face outside the body of open faces connected to vertex `start`: an island (a
  /// pair of vertices above h = 1 off the star's tip near its Roche limit) carries a potential of its
  /// own that the gauge does not fix, and made the system singular (relative residuals of 1e-4
  /// after factorisation).
  void keep_connected(const std::array<int, 3>& start) {
    const Level& lv = lat_.lv;
    std::vector<std::uint8_t> reached(lv.size, 0);
    std::vector<std::array<int, 3>> stack{start};
    reached[lat_.image(start[0], start[1], start[2])] = 1;
    while (!stack.empty()) {
      const auto [i, j, k] = stack.back();
      stack.pop_back();
      for (int d = 0; d < 3; ++d)
        for (int sgn : {-1, 1}) {
          const int ia = i + sgn * unit[d][0], ja = j + sgn * unit[d][1], ka = k + sgn * unit[d][2];
          const double a = sgn > 0 ? a_face(i, j, k, d) : a_face(ia, ja, ka, d);
          if (!(a > 0) || !in_box(ia, ja, ka)) continue;
          const Index q = lat_.image(ia, ja, ka);
          if (reached[q]) continue;
          reached[q] = 1;
          stack.push_back({ia, ja, lv.z_symmetry ? std::abs(ka) : ka});
        }
    }
    for (int d = 0; d < 3; ++d)
      for (std::size_t q = 0; q < lv.size; ++q)
        if (!reached[q]) face_a_[d][q] = 0.0;
    physical_ = std::move(reached);
  }

  /// Keeps the held vertices of the box in the system.
  void hold(const std::uint8_t* held) {
    if (!held) return;
    for (int k = std::max(c_.box[2][0], 0); k <= c_.box[2][1]; ++k)
      for (int j = c_.box[1][0]; j <= c_.box[1][1]; ++j)
        for (int i = c_.box[0][0]; i <= c_.box[0][1]; ++i)
          if (held[lat_.at(i, j, k)]) physical_[lat_.at(i, j, k)] = 1;
  }

  double largest_face() const {
    double a = 0;
    for (int d = 0; d < 3; ++d)
      for (const double f : face_a_[d]) a = std::max(a, f);
    return a;
  }

  bool physical(int i, int j, int k) const { return in_box(i, j, k) && physical_[lat_.image(i, j, k)]; }

  double a_face(int i, int j, int k, int d) const {
    if (d == 2 && k == -1 && lat_.lv.z_symmetry) return face_a_[2][lat_.at(i, j, 0)];
    if (!in_box(i, j, k)) return 0.0;
    return face_a_[d][lat_.at(i, j, k)];
  }

  /// D_t Psi at vertex (i, j, k), physical neighbours only, as (unknown, coefficient) pairs.
  void tangential(int i, int j, int k, int t, double scale, std::vector<std::pair<Index, double>>& out) const {
    const int ti = unit[t][0], tj = unit[t][1], tk = unit[t][2];
    const bool up = physical(i + ti, j + tj, k + tk), down = physical(i - ti, j - tj, k - tk);
    const double dx = lat_.lv.dx;
    const Index here = lat_.image(i, j, k), plus = lat_.image(i + ti, j + tj, k + tk), minus = lat_.image(i - ti, j - tj, k - tk);
    if (up && down) {
      out.push_back({plus, scale / (2 * dx)});
      out.push_back({minus, -scale / (2 * dx)});
    } else if (up) {
      out.push_back({plus, scale / dx});
      out.push_back({here, -scale / dx});
    } else if (down) {
      out.push_back({here, scale / dx});
      out.push_back({minus, -scale / dx});
    }
  }

  /// The flux through the face from (i, j, k) along d.
  FaceFlux flux(int i, int j, int k, int d) const {
    FaceFlux f;
    f.a = a_face(i, j, k, d);
    if (!(f.a > 0)) return f;
    const int i1 = i + unit[d][0], j1 = j + unit[d][1], k1 = k + unit[d][2];
    const Index p0 = lat_.at(i, j, k), p1 = lat_.at(i1, j1, k1);
    const Level& lv = lat_.lv;
    // Means of the end-node values; xi exactly at the face.
    const double alpha2 = 0.5 * (c_.alpha[p0] * c_.alpha[p0] + c_.alpha[p1] * c_.alpha[p1]);
    const double phi4 = 0.5 * (std::pow(c_.phi[p0], 4) + std::pow(c_.phi[p1], 4));
    const double xf = lv.x(i) + 0.5 * lv.dx * unit[d][0], yf = lv.y(j) + 0.5 * lv.dx * unit[d][1];
    const double xi[3] = {-yf, xf, 0.0};
    double beta[3] = {0.0, 0.0, 0.0}, b[3];
    for (int q = 0; q < 3; ++q) {
      if (c_.beta[q]) beta[q] = 0.5 * (c_.beta[q][p0] + c_.beta[q][p1]);
      b[q] = beta[q] + c_.omega_hat * xi[q];
    }
    const double dx = lv.dx;
    const double m_nn = alpha2 - phi4 * b[d] * b[d];
    f.terms.push_back({lat_.image(i1, j1, k1), f.a * m_nn / dx});
    f.terms.push_back({lat_.image(i, j, k), -f.a * m_nn / dx});
    for (int t = 0; t < 3; ++t) {
      if (t == d) continue;
      const double m_nt = -phi4 * b[d] * b[t];
      if (m_nt == 0) continue;
      tangential(i, j, k, t, 0.5 * f.a * m_nt, f.terms);
      tangential(i1, j1, k1, t, 0.5 * f.a * m_nt, f.terms);
    }
    f.constant = -f.a * phi4 * beta[d];
    f.constant_xi = -f.a * phi4 * xi[d];
    return f;
  }

  const std::vector<std::uint8_t>& physical_map() const { return physical_; }

 private:
  Lattice lat_;
  const Eos& eos_;
  const PotentialCoefficients& c_;
  const PotentialSettings& settings_;
  std::vector<std::uint8_t> physical_;
  std::vector<double> face_a_[3];
};

/// Fills every vertex of the box (widened by one point) that is not in `set`, layer by layer from
/// the set ones: the first `linear` layers by linear extrapolation from their set neighbours, the
/// rest by the mean of them (bounded, where extrapolation would grow). The start of vertices that
/// join the star, and what the centred gradients next to it read; no value from an earlier solve
/// survives near the star (the star may shrink between solves).
void extend(const Level& lv, double* psi, std::vector<std::uint8_t> set, const std::array<std::array<int, 2>, 3>& box,
            int linear) {
  auto inside = [&](int i, int j, int k) {
    return i >= 1 && i <= lv.nx - 2 && j >= 1 && j <= lv.ny - 2 && k >= (lv.z_symmetry ? -1 : 1) && k <= lv.nz - 2;
  };
  auto image = [&](int i, int j, int k) { return lv.at(i, j, lv.z_symmetry ? std::abs(k) : k); };
  const int k0 = std::max(box[2][0] - 1, lv.z_symmetry ? 0 : 1), k1 = std::min(box[2][1] + 1, lv.nz - 2);
  const int j0 = std::max(box[1][0] - 1, 1), j1 = std::min(box[1][1] + 1, lv.ny - 2);
  const int i0 = std::max(box[0][0] - 1, 1), i1 = std::min(box[0][1] + 1, lv.nx - 2);
  for (int layer = 0;; ++layer) {
    std::vector<std::pair<Index, double>> found;
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const Index p = lv.at(i, j, k);
          if (set[p]) continue;
          double sum = 0;
          int count = 0;
          for (int d = 0; d < 3; ++d)
            for (int sgn : {-1, 1}) {
              const int ia = i + sgn * unit[d][0], ja = j + sgn * unit[d][1], ka = k + sgn * unit[d][2];
              if (!inside(ia, ja, ka) || !set[image(ia, ja, ka)]) continue;
              const int ib = ia + sgn * unit[d][0], jb = ja + sgn * unit[d][1], kb = ka + sgn * unit[d][2];
              const double v1 = psi[image(ia, ja, ka)];
              sum += layer < linear && inside(ib, jb, kb) && set[image(ib, jb, kb)] ? 2 * v1 - psi[image(ib, jb, kb)] : v1;
              ++count;
            }
          if (count) found.push_back({p, sum / count});
        }
    if (found.empty()) break;
    for (const auto& [p, v] : found) {
      psi[p] = v;
      set[static_cast<std::size_t>(p)] = 1;
    }
  }
}

using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

struct Solution {
  Eigen::VectorXd x;
  int iterations = 0;
  double residual = 0;
  bool factorised = false;  ///< by the sparse LU: its residual is the rounding floor of the system
};

double relative_residual(const Matrix& matrix, const Eigen::VectorXd& x, const Eigen::VectorXd& rhs) {
  const double norm = rhs.norm();
  return norm > 0 ? (matrix * x - rhs).norm() / norm : (matrix * x).norm();
}

/// matrix x = rhs to the relative tolerance with BiCGSTAB (cheapest where it converges).
Solution bicgstab(const Matrix& matrix, const Eigen::VectorXd& rhs, const Eigen::VectorXd& guess, const PotentialSettings& settings) {
  Solution out;
  if (!(rhs.norm() > 0)) {
    out.x = Eigen::VectorXd::Zero(rhs.size());
    return out;
  }
  Eigen::BiCGSTAB<Matrix, Eigen::DiagonalPreconditioner<double>> solver;
  solver.setTolerance(settings.tolerance);
  solver.setMaxIterations(settings.max_iterations);
  solver.compute(matrix);
  out.x = solver.solveWithGuess(rhs, guess);
  out.iterations = static_cast<int>(solver.iterations());
  out.residual = relative_residual(matrix, out.x, rhs);
  return out;
}

/// Both right-hand sides of one operator. BiCGSTAB stalls or breaks down on some of these
/// nonsymmetric systems (thousands of iterations next to a star whose surface faces are barely
/// open); then a sparse LU factorisation (with two steps of iterative refinement: the mean-value
/// coupling of closed vertices leaves the system ill-conditioned) up to `direct_limit` unknowns,
/// where it takes a second or two, and restarted GMRES above.
std::array<Solution, 2> solve(const Matrix& matrix, const Eigen::VectorXd& rhs, const Eigen::VectorXd& rhs_xi,
                              const Eigen::VectorXd& guess, const Eigen::VectorXd& guess_xi, const PotentialSettings& settings) {
  std::array<Solution, 2> out{bicgstab(matrix, rhs, guess, settings), bicgstab(matrix, rhs_xi, guess_xi, settings)};
  const double accept = 10 * settings.tolerance;
  if (out[0].residual <= accept && out[1].residual <= accept) return out;
  const Eigen::VectorXd* sources[2] = {&rhs, &rhs_xi};
  const Eigen::VectorXd* guesses[2] = {&guess, &guess_xi};
  if (matrix.rows() <= settings.direct_limit) {
    const Eigen::SparseMatrix<double> columns(matrix);
    Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
    lu.compute(columns);
    if (lu.info() != Eigen::Success) return out;
    for (int r = 0; r < 2; ++r) {
      if (out[r].residual <= accept) continue;
      Eigen::VectorXd x = lu.solve(*sources[r]);
      for (int step = 0; step < 2; ++step) x += lu.solve(*sources[r] - matrix * x);
      out[r].x = x;
      out[r].factorised = true;
      out[r].residual = relative_residual(matrix, x, *sources[r]);
    }
    return out;
  }
  for (int r = 0; r < 2; ++r) {
    if (out[r].residual <= accept) continue;
    Eigen::GMRES<Matrix, Eigen::DiagonalPreconditioner<double>> gmres;
    gmres.set_restart(60);
    gmres.setTolerance(settings.tolerance);
    gmres.setMaxIterations(settings.max_iterations);
    gmres.compute(matrix);
    out[r].x = gmres.solveWithGuess(*sources[r], *guesses[r]);
    out[r].iterations += static_cast<int>(gmres.iterations());
    out[r].residual = relative_residual(matrix, out[r].x, *sources[r]);
  }
  return out;
}

}  // namespace

PotentialSolve solve_potential(Grid& grid, int psi_field, double* psi_xi, const Eos& eos, const PotentialCoefficients& c,
                               const PotentialSettings& settings) {
  const Level& lv = grid.finest();
  double* psi = grid.data(psi_field, 0, 0);
  const Lattice lat{lv};
  Operator op(lv, eos, c, settings);
  op.classify();
  // The gauge vertex (Psitilde = 0 there): the vertex with an open face nearest the star's centre.
  // The body of open faces connected to it is the system.
  PotentialSolve out;
  std::array<int, 3> gauge_vertex{-1, -1, -1};
  double nearest = 1e300;
  for (int k = std::max(c.box[2][0], 0); k <= c.box[2][1]; ++k)
    for (int j = c.box[1][0]; j <= c.box[1][1]; ++j)
      for (int i = c.box[0][0]; i <= c.box[0][1]; ++i) {
        if (!op.physical(i, j, k)) continue;
        const double d = std::hypot(lv.x(i) - c.centre[0], lv.y(j) - c.centre[1], lv.z(k) - c.centre[2]);
        if (d < nearest) nearest = d, gauge_vertex = {i, j, k};
      }
  if (gauge_vertex[0] < 0) {
    out.converged = true;
    return out;
  }
  op.keep_connected(gauge_vertex);
  op.hold(c.held_system);
  const double coupling = settings.coupling * op.largest_face();
  const std::vector<std::uint8_t>& physical = op.physical_map();
  // The unknowns: the physical vertices (stored points).
  std::vector<Index> column(lv.size, -1);
  std::vector<std::array<int, 3>> vertex;
  for (int k = c.box[2][0]; k <= c.box[2][1]; ++k)
    for (int j = c.box[1][0]; j <= c.box[1][1]; ++j)
      for (int i = c.box[0][0]; i <= c.box[0][1]; ++i)
        if (k >= 0 && physical[lv.at(i, j, k)]) {
          column[lv.at(i, j, k)] = static_cast<Index>(vertex.size());
          vertex.push_back({i, j, k});
        }
  out.unknowns = static_cast<int>(vertex.size());
  const auto gauge = static_cast<std::size_t>(column[lv.at(gauge_vertex[0], gauge_vertex[1], gauge_vertex[2])]);
  const auto n = static_cast<Eigen::Index>(vertex.size());
  std::vector<Eigen::Triplet<double>> triplets;
  // Two right-hand sides for one operator (M at the given Omegahat): the shift's source and the
  // rotation's per unit Omegahat; Psitilde = Psitilde_beta + Omegahat Psitilde_xi.
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n), rhs_xi = Eigen::VectorXd::Zero(n), guess(n), guess_xi(n);
  for (std::size_t q = 0; q < vertex.size(); ++q) {
    const auto [i, j, k] = vertex[q];
    const auto row = static_cast<Eigen::Index>(q);
    guess[row] = psi[lv.at(i, j, k)] - c.omega_hat * psi_xi[lv.at(i, j, k)];
    guess_xi[row] = psi_xi[lv.at(i, j, k)];
    if (q == gauge) {
      triplets.emplace_back(row, row, 1.0);
      continue;
    }
    // R_v = sum_d (F(v, v + e_d) - F(v - e_d, v)) / dx, each row scaled by its diagonal below.
    std::vector<std::pair<Index, double>> terms;
    double constant = 0, constant_xi = 0;
    for (int d = 0; d < 3; ++d) {
      const FaceFlux up = op.flux(i, j, k, d);
      const FaceFlux down = op.flux(i - unit[d][0], j - unit[d][1], k - unit[d][2], d);
      for (const auto& t : up.terms) terms.push_back(t);
      for (const auto& t : down.terms) terms.push_back({t.first, -t.second});
      constant += up.constant - down.constant;
      constant_xi += up.constant_xi - down.constant_xi;
    }
    std::vector<Index> neighbours;
    for (int d = 0; d < 3; ++d)
      for (int sgn : {-1, 1}) {
        const int ia = i + sgn * unit[d][0], ja = j + sgn * unit[d][1], ka = k + sgn * unit[d][2];
        if (op.physical(ia, ja, ka)) neighbours.push_back(lat.image(ia, ja, ka));
      }
    if (!neighbours.empty()) {
      terms.push_back({lv.at(i, j, k), coupling});
      for (const Index p : neighbours) terms.push_back({p, -coupling / static_cast<double>(neighbours.size())});
    }
    double diagonal = 0;
    for (const auto& [p, v] : terms)
      if (p == lv.at(i, j, k)) diagonal += v;
    const double scale = diagonal != 0 ? 1.0 / std::fabs(diagonal) : 1.0;
    for (const auto& [p, v] : terms) triplets.emplace_back(row, static_cast<Eigen::Index>(column[static_cast<std::size_t>(p)]), v * scale);
    rhs[row] = -constant * scale;
    rhs_xi[row] = -constant_xi * scale;
  }
  Matrix matrix(n, n);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  for (Eigen::Index q = 0; q < matrix.nonZeros(); ++q)
    if (!std::isfinite(matrix.valuePtr()[q]))
      throw core::RunFailure("flow_irrotational: a non-finite coefficient in the velocity potential's equation (the "
                             "fields about the star are not finite)");
  const auto [beta_part, xi_part] = solve(matrix, rhs, rhs_xi, guess, guess_xi, settings);
  out.iterations = beta_part.iterations + xi_part.iterations;
  out.residual = std::max(beta_part.residual, xi_part.residual);
  // A factorised solution is as good as the system's conditioning allows (a relative residual of
  // 1e-8 to 1e-7 where closed vertices hang on by the mean-value coupling); only a gross one fails.
  auto accepted = [&](const Solution& s) { return s.residual <= 10 * settings.tolerance || (s.factorised && s.residual <= 1e-6); };
  out.converged = accepted(beta_part) && accepted(xi_part);
  // Outside the star (s <= 0) the physical vertices touch it only through faces of small a, and a
  // vertex held by one such face carries the one-sided zero-flux condition d_n Psitilde = phi^4 B^n/M^nn,
  // an O(1) error in its gradient that the vanishing a keeps out of the star. Its value is therefore
  // not extended from: the extension starts from the star's own vertices, smooth up to the surface.
  out.system.assign(lv.size, 0);
  out.source.assign(lv.size, 0);
  for (std::size_t q = 0; q < vertex.size(); ++q) {
    const Index p = lv.at(vertex[q][0], vertex[q][1], vertex[q][2]);
    const auto row = static_cast<Eigen::Index>(q);
    psi_xi[p] = xi_part.x[row];
    psi[p] = beta_part.x[row] + c.omega_hat * xi_part.x[row];
    out.system[static_cast<std::size_t>(p)] = 1;
    out.source[static_cast<std::size_t>(p)] = c.level_set[p] > 0 || (c.held_source && c.held_source[p]);
  }
  extend(lv, psi, out.source, c.box, settings.extension_cells);
  extend(lv, psi_xi, out.source, c.box, settings.extension_cells);
  grid.fill_ghosts(psi_field, 0);
  grid.fill_ghosts(psi_xi, Parity{}, 0);
  return out;
}

}  // namespace bhnsid::flow_irrotational
