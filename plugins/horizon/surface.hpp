#pragma once
// A star-shaped surface about the puncture, r = h(theta, phi) = sum a_lm Y_lm(theta, phi), in
// orthonormal real spherical harmonics up to l_max; with equatorial symmetry (z -> -z) only the
// terms with l + m even, which are the even ones. Its collocation and quadrature points are Gauss-Legendre
// in cos(theta) times equally spaced in phi, exact for the band-limited parts of the integrands.
#include <array>
#include <vector>

namespace bhnsid::horizon {

struct Mode {
  int l, m;  ///< m < 0: sin(|m| phi), m > 0: cos(m phi)
};

/// Y_lm(theta, phi), orthonormal on the unit sphere.
double real_harmonic(const Mode& mode, double theta, double phi);

struct SurfacePoint {
  double theta, phi, weight;  ///< weight: the quadrature weight of d(cos theta) d phi
};

class SurfaceBasis {
 public:
  SurfaceBasis(int l_max, bool equatorial);

  const std::vector<Mode>& modes() const { return modes_; }
  const std::vector<SurfacePoint>& points() const { return points_; }
  /// h at (theta, phi) for the coefficients a.
  double radius(const std::vector<double>& a, double theta, double phi) const;
  /// The coefficients of the sphere r = r0.
  std::vector<double> sphere(double r0) const;
  /// The index of mode (l, m), or -1.
  int find(int l, int m) const;
  int l_max() const { return l_max_; }

 private:
  int l_max_;
  std::vector<Mode> modes_;
  std::vector<SurfacePoint> points_;
};

}  // namespace bhnsid::horizon
