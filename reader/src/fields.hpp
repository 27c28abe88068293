#pragma once
// The Einstein Toolkit fields at a point, from the stored data: what is interpolated and what is
// computed (the puncture's pole, the EOS, the Lorentz factor). reader/README.md states the rules.
#include <string>
#include <vector>

#include "data_file.hpp"
#include "lagrange.hpp"

namespace bhnsid::reader {

/// The ETK names bhnsid_reader_interpolate() knows, in the table's order.
const std::vector<std::string>& etk_field_names();

/// Those that `file` can answer (for bhnsid_reader_field_name): every one but press and eps
/// without EOS formulas, and the fields whose stored data are missing (alp, the metric, the fluid).
std::vector<std::string> available_fields(const DataFile& file);

/// A set of requested fields, resolved once (names checked, datasets loaded); evaluate() is pure
/// and may run from several threads at once.
class Request {
 public:
  /// Throws ERR_ARGUMENT for an unknown name, ERR_NOT_FOUND for missing data, ERR_EOS for press or
  /// eps without formulas. check_only: only those checks, nothing loaded (evaluate() then must
  /// not be called).
  Request(const DataFile& file, const std::vector<std::string>& names, bool check_only = false);
  /// out[f] = field f at the stencil's point (number `index`, for messages). Throws ERR_PUNCTURE
  /// at the puncture, ERR_VALUE for |v| >= 1 or phi <= 0, ERR_OUTSIDE where an extrapolated value
  /// is not finite (the point too far outside the grid).
  void evaluate(const Stencil& s, std::size_t index, double* out) const;

 private:
  enum class Kind { raw, lapse, shift, metric, curvature, rho, press, eps, vel, w_lorentz };
  struct Item {
    Kind kind;
    int component = 0;          // shift/vel: 0..2; metric/curvature: xx xy xz yy yz zz = 0..5
    const Field* data = nullptr;  // what is interpolated; null: zero
    std::string name;             // as asked, for messages
  };
  struct Point;
  void metric(const Stencil& s, std::size_t index, Point& p) const;
  double density(const Stencil& s, Point& p) const;

  const DataFile& file_;
  std::vector<Item> items_;
  bool puncture_ = false;
  double bh_mass_ = 0;
  std::array<double, 3> bh_position_{};
  const Field* chi_ = nullptr;
  const Field* eta_ = nullptr;       // eta, or lapse_komar's eta~
  double lapse_strength_ = 0;        // c of alp phi = eta - c M/(2r)
  std::array<const Field*, 6> metric_{};  // stored g_ij without a puncture
  const Field* rho_ = nullptr;            // null: vacuum
  std::array<const Field*, 3> vel_{};
};

/// P and eps of the piecewise polytrope at rho >= 0 (0 and 0 at rho = 0).
void eos_at(const PiecewisePolytrope& eos, double rho, double& press, double& eps);

}  // namespace bhnsid::reader
