#pragma once
// An elliptic equation as the multigrid solver sees it: one unknown grid field (1 or 3 components)
// with a nonlinear operator L, solved for L(u) = 0 on the finest level. The solver owns everything
// else: the right-hand sides that FAS puts on coarse levels, restriction of the coefficient fields,
// the outer-boundary rows and the excision points. Equation plugins publish one EllipticEquation
// service each, under a capability named "equation.NAME"; the solver relaxes all of them together.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bhnsid/core/services.hpp"

namespace bhnsid {

/// MemoryEstimate::count key: the unknown components of every equation, from which the solver
/// estimates its scratch fields and its coarsest-level direct solve.
inline constexpr const char* memory_unknown_components = "elliptic.unknown_components";

/// Condition on the outer faces of the cube, per component.
struct OuterBoundary {
  enum class Kind {
    /// (u - u_inf) + (x - centre) . grad u = 0: exact for u_inf + f(angles)/|x - centre|
    /// (physics-notes §5.2); one-sided second-order normal derivatives, relaxed with the system.
    robin,
    /// u keeps the values it has on the faces of the finest level when the solve starts.
    dirichlet,
  } kind = Kind::robin;
  std::vector<double> u_inf;       ///< asymptotic value per component (robin)
  std::array<double, 3> centre{};  ///< centre of the 1/r falloff (robin)
};

/// What one relaxation or operator call works on.
struct RelaxArgs {
  int level = 0;
  /// FAS right-hand side per component; nullptr means zero (the finest level).
  const double* const* rhs = nullptr;
  /// 1 where the point is held at its value (excision), 0 elsewhere; nullptr means no such point.
  const std::uint8_t* fixed = nullptr;
  /// relax() moves each point by omega times its Newton step. Over-relaxed red-black smoothing
  /// (omega ~ 1.15 in 3-D, Yavneh 1996) damps high frequencies much better than omega = 1.
  double omega = 1.0;
};

class EllipticEquation : public core::Service {
 public:
  ~EllipticEquation() override;  ///< defined in the core library, like Grid's (see grid.hpp)
  /// Short name used in reports ("hamiltonian", "momentum", ...).
  virtual std::string name() const = 0;
  /// The grid field this equation solves for (registered by the equation on all levels).
  virtual std::string unknown() const = 0;
  virtual OuterBoundary boundary() const = 0;
  /// Name of the grid mask (Grid::add_mask) whose points keep their values; empty for none.
  virtual std::string excision_mask() const { return {}; }
  /// Fields the operator reads but does not solve for; the solver restricts them to every level
  /// by full weighting before each solve. Other equations' unknowns need not be listed.
  virtual std::vector<std::string> coefficients() const = 0;
  /// What a failed solve most likely means for this equation, appended to the solver's failure
  /// message (e.g. the Hamiltonian constraint's fold); empty for nothing to add.
  virtual std::string failure_hint() const { return {}; }

  /// out[c] = rhs_c - L(u)_c at every interior point of the level (Level::k_begin() .. nz-2 in z,
  /// 1 .. n-1 in x and y), with rhs == nullptr read as zero, and out = 0 at fixed points. The
  /// ghosts of every field read are current when this is called.
  virtual void residual(const RelaxArgs& args, double* const* out) const = 0;
  /// One red-black nonlinear Gauss-Seidel sweep over the interior, non-fixed points: first every
  /// point with (i + j + k) even, then every odd one, each moved by omega times one Newton step on
  /// its own unknowns (a 3x3 solve for a vector) toward L(u) = rhs, all other values held. Both
  /// colours in one call let the kernel fuse them plane by plane (stencil::red_black_sweep), so
  /// the fields stream through memory once per sweep. Ghosts are current on entry; the solver
  /// refreshes them after the call.
  virtual void relax(const RelaxArgs& args) const = 0;
};

}  // namespace bhnsid
