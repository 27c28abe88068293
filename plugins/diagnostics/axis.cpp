#include "axis.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"

namespace bhnsid::diagnostics {

namespace {

struct Column {
  std::string name;
  const double* values;
};

std::vector<Column> columns(Grid& grid, const Lapse* lapse) {
  std::vector<Column> out;
  // The lapse's own unknown (its regular part) and alpha, refreshed from it, beside the others.
  std::vector<std::string> names{fields::chi};
  if (lapse) {
    names.push_back(lapse->regular_part());
    lapse->update(grid, 0);
    names.push_back(fields::alpha);
  }
  for (const char* name : {fields::wvec, fields::shift, fields::rho0}) names.push_back(name);
  for (const std::string& name : names) {
    if (!grid.has_field(name)) continue;
    const int id = grid.field_id(name);
    const auto& info = grid.field_info(id);
    for (std::size_t c = 0; c < info.components.size(); ++c)
      out.push_back({info.components.size() == 1 ? std::string(name) : fmt::format("{}_{}", name, "xyz"[c]),
                     grid.data(id, static_cast<int>(c), 0)});
  }
  return out;
}

}  // namespace

std::string axis_table(Grid& grid, const Lapse* lapse) {
  const std::vector<Column> cols = columns(grid, lapse);
  std::string out = "# x";
  for (const Column& c : cols) out += "\t" + c.name;
  out += "\n";
  std::vector<std::vector<std::array<double, 2>>> lines;
  for (const Column& c : cols) lines.push_back(grid.line_x(c.values, 0));
  const std::size_t n = lines.empty() ? 0 : lines[0].size();
  for (std::size_t i = 0; i < n; ++i) {
    out += fmt::format("{:.10g}", lines[0][i][0]);
    for (const auto& line : lines) out += fmt::format("\t{:.12e}", line[i][1]);
    out += "\n";
  }
  return out;
}

std::map<std::string, double> deviations(const Grid& grid, const Lapse* lapse) {
  const Level& lv = grid.finest();
  auto largest = [&](const double* v, double offset) {
    double m = 0;
#pragma omp parallel for schedule(static) reduction(max : m)
    for (int k = 0; k < lv.nz; ++k)
      for (int j = 0; j < lv.ny; ++j) {
        const double* row = v + lv.at(0, j, k);
#pragma omp simd reduction(max : m)
        for (int i = 0; i < lv.nx; ++i) m = std::max(m, std::fabs(row[i] - offset));
      }
    return m;
  };
  std::map<std::string, double> out;
  std::vector<std::string> scalars{fields::chi};
  if (lapse) scalars.push_back(lapse->regular_part());
  for (const std::string& field : scalars)
    if (grid.has_field(field)) out[field + "_deviation_max"] = largest(grid.data(grid.field_id(field), 0, 0), 1.0);
  const std::pair<const char*, const char*> vectors[] = {{fields::wvec, "wvec_max"}, {fields::shift, "shift_max"}};
  for (const auto& [field, key] : vectors)
    if (grid.has_field(field)) {
      double m = 0;
      for (int c = 0; c < 3; ++c) m = std::max(m, largest(grid.data(grid.field_id(field), c, 0), 0.0));
      out[key] = m;
    }
  return out;
}

}  // namespace bhnsid::diagnostics
