#pragma once
// The contract between an independent residual evaluator and `bhnsid validate`, so that the core
// refines and judges a configuration without knowing its plugins or its equations. A plugin that
// implements the capability below writes, at ANALYSIS, for every equation E it evaluates, the
// summary.json scalars
//   residual_E_l2, residual_E_max      the norms away from the regions where no convergence is due,
//   residual_E_surface_l2 (optional)   the norm in a band where the order is reduced (a star's surface),
//   residual_E_judged                  1: expected to converge at second order; 0: reported only,
// and at OUTPUT the file residual_axis.tsv: a header "# x<TAB>column...<TAB>region", then one row
// per x-axis point (the points of the coarsest run: every run evaluates there), "nan" where a
// residual is not defined. Which parameters follow the resolution the plugins declare themselves
// (ParamHandle::refines).
#include <string>

namespace bhnsid::core::residual_report {

inline constexpr const char* capability = "residual_evaluator";
inline constexpr const char* axis_file = "residual_axis.tsv";
inline constexpr const char* prefix = "residual_";

/// "residual_" + equation + "_" + what.
inline std::string key(const std::string& equation, const char* what) {
  std::string k = prefix;
  k += equation;
  k += '_';
  k += what;
  return k;
}

}  // namespace bhnsid::core::residual_report
