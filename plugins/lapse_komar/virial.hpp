#pragma once
// The strength c of the lapse's singular term from the virial condition M_Komar = M_ADM, the
// quasi-equilibrium condition of helically symmetric data. Far away eta = alpha phi ~ 1 + B_eta/r
// and phi ~ 1 + B_phi/r, so alpha ~ 1 + (B_eta - B_phi)/r: M_Komar = sigma (B_phi - B_eta) and
// M_ADM = 2 sigma B_phi, and the condition is B_eta + B_phi = 0. Both B are 1/r coefficients
// (FalloffFit, extrapolated over cube surfaces) of the regular fields with the puncture's own 1/r
// added exactly: B_eta = B(eta~) - c Mhat/2, B_phi = B(chi) + Mhat/2.
#include <array>
#include <optional>

#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::lapse_komar {

struct VirialMeasure {
  double b_eta = 0, b_phi = 0;  ///< hatted 1/r coefficients of eta and phi
  double residual() const { return b_eta + b_phi; }
  /// M_Komar / M_ADM = (B_phi - B_eta) / (2 B_phi).
  double ratio() const { return (b_phi - b_eta) / (2.0 * b_phi); }
};

/// The coefficients from the finest level's eta~ and chi about `centre`, for the current c and the
/// hole's Mhat, over the cube surfaces that enclose the star and the hole; NaN when fewer than four do.
VirialMeasure measure_virial(const Grid& grid, double c, const Puncture& hole, const std::array<double, 3>& centre);

/// A secant on c for B_eta(c) + B_phi = 0 across outer iterations (the fields move with c and with
/// the rest of the outer iteration, so one exact root is never available; each step uses the latest
/// solve). The slope starts at its vacuum value -Mhat/2 and is replaced by the secant's once two
/// measurements exist, when that has the right sign.
class VirialSecant {
 public:
  /// The next c after a solve with `c` measured `m`; `fraction` < 1 shortens the step (after a retreat).
  double next(double c, const VirialMeasure& m, double bare_mass, double fraction);
  void forget() { last_.reset(); }

 private:
  struct Point {
    double c, g;
  };
  std::optional<Point> last_;
};

}  // namespace bhnsid::lapse_komar
