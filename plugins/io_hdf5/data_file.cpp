#include "data_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/interrupt.hpp"
#include "h5_file.hpp"

namespace bhnsid::io_hdf5 {

namespace {

/// The stored points of one finest-level array in C order (z slowest, x fastest), checked finite.
std::vector<double> stored_points(const Level& lv, const double* values, const std::string& path) {
  std::vector<double> out(static_cast<std::size_t>(lv.nx) * lv.ny * lv.nz);
  std::size_t q = 0;
  for (int k = 0; k < lv.nz; ++k)
    for (int j = 0; j < lv.ny; ++j)
      for (int i = 0; i < lv.nx; ++i) {
        const double v = values[lv.at(i, j, k)];
        if (!std::isfinite(v))
          throw core::RunFailure(fmt::format("io_hdf5: {} is {} at point ({}, {}, {}); data.h5 is not written", path, v, i,
                                             j, k));
        out[q++] = v;
      }
  return out;
}

std::string component_name(const FieldInfo& info, std::size_t c) {
  return info.components.size() == 1 ? info.name : fmt::format("{}[{}]", info.name, c);
}

}  // namespace

DataFile write_data_file(const std::string& path, const Grid& grid, const std::vector<const FieldExport*>& exports, const core::RunRecord& record,
                         const EosRecord& eos, double sigma, const Settings& settings) {
  const Level& lv = grid.finest();
  DataFile out;
  out.geometry = {lv.nx, lv.ny, lv.nz, sigma * lv.dx, {sigma * lv.origin[0], sigma * lv.origin[1], sigma * lv.origin[2]}};
  const std::array<hsize_t, 3> dims{static_cast<hsize_t>(lv.nz), static_cast<hsize_t>(lv.ny), static_cast<hsize_t>(lv.nx)};
  H5File file(path);
  const hid_t root = file.root();
  file.attribute(root, "format", std::string("bhnsid-data"));
  file.attribute(root, "format_version", format_version);
  // A stopping signal without a failure: the last state of an interrupted run, not a solution.
  const char* status = !record.failure.empty() ? "failed" : core::interrupt_signal() != 0 ? "interrupted" : "converged";
  file.attribute(root, "status", std::string(status));
  file.attribute(root, "failure", record.failure);
  file.attribute(root, "units", std::string(eos.eos ? eos.eos->units().system : "G = c = 1"));

  const hid_t g = file.group("/grid");
  file.attribute(g, "shape_zyx", std::vector<double>{double(lv.nz), double(lv.ny), double(lv.nx)});
  file.attribute(g, "dx", out.geometry.dx);
  file.attribute(g, "origin_xyz", std::vector<double>(out.geometry.origin.begin(), out.geometry.origin.end()));
  file.attribute(g, "sigma", sigma);
  file.attribute(g, "dx_hat", lv.dx);
  file.attribute(g, "symmetry", std::string(lv.z_symmetry ? "equatorial" : "none"));
  file.attribute(g, "layout",
                 std::string("vertex-centred uniform grid; point (i, j, k) at origin_xyz + dx (i, j, k); datasets are "
                             "[k][j][i] (C order, x fastest); physical coordinates x = sigma xhat"));

  // The Einstein Toolkit's variables, one group per thorn, as the owning plugins publish them.
  std::vector<double> buffer(lv.size);
  std::set<std::string> groups;
  for (const FieldExport* e : exports) {
    const std::vector<ExportField> fields = e->export_fields();
    for (std::size_t f = 0; f < fields.size(); ++f) {
      const ExportField& field = fields[f];
      if (groups.insert(field.group).second) file.group("/" + field.group);
      const std::string path = "/" + field.group + "/" + field.name;
      if (!field.same_as.empty()) {
        file.link("/" + field.group + "/" + field.same_as, path);
        out.datasets.push_back(path);
        continue;
      }
      std::fill(buffer.begin(), buffer.end(), 0.0);
      e->fill(f, buffer.data());
      const hid_t d = file.dataset(root, path.substr(1), dims, stored_points(lv, buffer.data(), path), settings.compression);
      file.attribute(d, "units", field.units);
      file.attribute(d, "parity_z", static_cast<long long>(field.parity.z));
      file.attribute(d, "description", field.doc);
      if (const std::optional<ExcisionRegion> held = e->held_region(f)) {
        file.attribute(d, "held_region_shape", std::string(held->shape == ExcisionRegion::Shape::cube ? "cube" : "sphere"));
        file.attribute(d, "held_region_centre", std::vector<double>(held->centre.begin(), held->centre.end()));
        file.attribute(d, "held_region_half_size", held->half_size);
      }
      out.datasets.push_back(path);
    }
  }

  // The code's own fields (hatted units, the solver's variables), for restarts and inspection.
  if (settings.all_variables || !settings.variables.empty()) {
    const hid_t v = file.group("/variables");
    file.attribute(v, "description", std::string("the solver's fields on the finest level, in hatted units (xhat = x / "
                                                 "sigma); the matter fields are never rescaled"));
    for (int id = 0; id < grid.num_fields(); ++id) {
      const FieldInfo& info = grid.field_info(id);
      if (info.storage == core::Storage::coarse_levels) continue;
      if (!settings.all_variables &&
          std::find(settings.variables.begin(), settings.variables.end(), info.name) == settings.variables.end())
        continue;
      for (std::size_t c = 0; c < info.components.size(); ++c) {
        const std::string name = component_name(info, c);
        const std::string path = "/variables/" + name;
        const hid_t d = file.dataset(v, name, dims, stored_points(lv, grid.data(id, static_cast<int>(c), 0), path),
                                     settings.compression);
        file.attribute(d, "tensor_kind", std::string(core::to_string(info.components[c])));
        file.attribute(d, "parity_z", static_cast<long long>(info.parity[c].z));
        out.datasets.push_back(path);
      }
    }
  }

  // Every scalar the plugins set (masses, Omega, momenta, E_b, J, the IRE's norms, ...), physical
  // unless its name ends in _hat; a non-finite one is listed instead of stored.
  const hid_t sc = file.group("/scalars");
  std::string non_finite;
  for (const auto& [name, value] : record.scalars) {
    if (std::isfinite(value))
      file.attribute(sc, name, value);
    else
      non_finite += (non_finite.empty() ? "" : " ") + name;
  }
  file.attribute(sc, "non_finite", non_finite);

  const hid_t eg = file.group("/eos");
  file.attribute(eg, "plugin", eos.plugin);
  if (eos.eos) {
    const EosUnits u = eos.eos->units();
    file.attribute(eg, "description", eos.eos->describe());
    file.attribute(eg, "units", u.system);
    file.attribute(eg, "length_km", u.length_km);
    file.attribute(eg, "time_s", u.time_s);
    file.attribute(eg, "mass_msun", u.mass_msun);
    file.attribute(eg, "density_g_cm3", u.density_g_cm3);
    // The formulas themselves, so that a reader recomputes P and eps from rho alone.
    const std::vector<PolytropePiece> pieces = eos.eos->polytrope_pieces();
    file.attribute(eg, "model", std::string(pieces.empty() ? "other" : "piecewise_polytrope"));
    if (!pieces.empty()) {
      std::vector<double> lo, k, gamma, offset;
      for (const PolytropePiece& p : pieces) {
        lo.push_back(p.rho0_lo);
        k.push_back(p.k);
        gamma.push_back(p.gamma);
        offset.push_back(p.eps_offset);
      }
      file.attribute(eg, "rho0_lo", lo);
      file.attribute(eg, "K", k);
      file.attribute(eg, "Gamma", gamma);
      file.attribute(eg, "eps_offset", offset);
    }
  }

  const hid_t pg = file.group("/parameters");
  file.attribute(pg, "parameter_file", record.parameter_file);
  file.attribute(pg, "resolved", record.resolved_parameters);
  std::string plugins;
  for (const auto& [capability, plugin] : record.implementations) plugins += fmt::format("{}: {}\n", capability, plugin);
  file.attribute(pg, "implementations", plugins);
  const hid_t prov = file.group("/provenance");
  for (const auto& [key, value] : record.provenance) file.attribute(prov, key, value);

  file.close();
  return out;
}

}  // namespace bhnsid::io_hdf5
