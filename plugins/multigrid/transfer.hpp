#pragma once
// Inter-level transfers of the FAS cycle. Coarse point I sits on fine point 2I; every kernel runs
// over planes with OpenMP and over contiguous rows in the innermost loop.
#include <cstdint>

#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid::multigrid {

/// c = full weighting of `f` minus `minus` at the coarse interior points (27-point stencil with
/// weights (1/2)^{|d|_1} / 8). Needs the fine ghosts filled; never reads fine face points, because
/// the stencil of an interior coarse point stays inside the fine interior.
/// With fold_faces (equations whose face rows are Robin rows, slaved to the interior), the weight
/// of the coarse face point goes to its interior neighbour.
void restrict_full_weighting_minus(const Level& fine, const Level& coarse, const double* f, const double* minus,
                                   double* c, bool fold_faces);

/// Same weights, overwriting the coarse interior and injecting at the coarse face points: for
/// coefficient fields, whose face values the interior stencils never read.
void restrict_full_weighting(const Level& fine, const Level& coarse, const double* f, double* c);

/// c = f at coincident points, all stored coarse points (faces included); the same into copy too
/// when given (the FAS start u_H^old, stored points only: nothing reads its ghosts).
void restrict_injection(const Level& fine, const Level& coarse, const double* f, double* c, double* copy = nullptr);

/// fine += trilinear interpolation of (coarse - coarse_old) at the fine points that are not held:
/// interior points, and face points too when `faces` (Robin rows are unknowns, Dirichlet rows not).
void prolong_correction(const Level& coarse, const Level& fine, const double* c, const double* c_old, double* f,
                        const std::uint8_t* fixed, bool faces);

}  // namespace bhnsid::multigrid

namespace bhnsid::multigrid {

/// As prolong_correction, with cubic interpolation (weights -1/16, 9/16, 9/16, -1/16 along each
/// axis at the midpoints; linear where the four coarse points do not exist). Used for the FMG
/// step, where the interpolated solution must already be accurate to the discretization error.
void prolong_correction_cubic(const Level& coarse, const Level& fine, const double* c, const double* c_old, double* f,
                              const std::uint8_t* fixed, bool faces);

}  // namespace bhnsid::multigrid
