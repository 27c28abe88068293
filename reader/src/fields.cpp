#include "fields.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bhnsid_reader.h"

namespace bhnsid::reader {

namespace {

const char* const metric_suffix[6] = {"xx", "xy", "xz", "yy", "yz", "zz"};
// (row, column) -> index into xx xy xz yy yz zz
constexpr int sym[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};

int tensor_index(const std::string& suffix) {
  for (int c = 0; c < 6; ++c)
    if (suffix == metric_suffix[c]) return c;
  return -1;
}

std::string point_text(std::size_t index, const Stencil& s) {
  std::ostringstream m;
  m.precision(17);
  m << "point " << index << " (" << s.point[0] << ", " << s.point[1] << ", " << s.point[2] << ")";
  return m.str();
}

}  // namespace

const std::vector<std::string>& etk_field_names() {
  static const std::vector<std::string> names = {
      "alp", "betax", "betay", "betaz", "gxx", "gxy", "gxz", "gyy", "gyz", "gzz", "kxx", "kxy",
      "kxz", "kyy", "kyz", "kzz", "rho", "press", "eps", "vel[0]", "vel[1]", "vel[2]", "w_lorentz"};
  return names;
}

std::vector<std::string> available_fields(const DataFile& file) {
  std::vector<std::string> out;
  for (const std::string& name : etk_field_names()) {
    try {
      Request r(file, {name}, /*check_only=*/true);
      out.push_back(name);
    } catch (const Error&) {
      // not answerable from this file: left out of the list
    }
  }
  return out;
}

void eos_at(const PiecewisePolytrope& eos, double rho, double& press, double& eps) {
  if (rho <= 0) {
    press = eps = 0;
    return;
  }
  std::size_t i = 0;
  while (i + 1 < eos.rho_lo.size() && rho >= eos.rho_lo[i + 1]) ++i;
  press = eos.k[i] * std::pow(rho, eos.gamma[i]);
  eps = eos.a[i] + eos.k[i] * std::pow(rho, eos.gamma[i] - 1) / (eos.gamma[i] - 1);
}

struct Request::Point {
  bool have_metric = false, have_rho = false;
  double phi = 0, pole = 0;  ///< phi and its puncture part M/(2r)
  std::array<double, 6> g{};
  double rho = 0;
};

Request::Request(const DataFile& file, const std::vector<std::string>& names, bool check_only) : file_(file) {
  const std::optional<double> mass = file.scalar("bh_bare_mass");
  puncture_ = mass && *mass > 0;
  const auto need = [&](const std::string& path, const std::string& why) -> const Field* {
    if (!file.has_dataset(path))
      throw Error(BHNSID_READER_ERR_NOT_FOUND, file.path() + " has no " + path + ", which " + why + " needs");
    return check_only ? nullptr : &file.field(path);
  };
  const auto optional = [&](const std::string& path) -> const Field* {
    return file.has_dataset(path) && !check_only ? &file.field(path) : nullptr;
  };
  bool metric_used = false, fluid_used = false;
  for (const std::string& name : names) {
    Item it{Kind::raw, 0, nullptr, name};
    if (!name.empty() && name[0] == '/') {
      it.data = need(name, "the request '" + name + "'");
    } else if (name == "alp") {
      it.kind = Kind::lapse;
      if (puncture_) {
        metric_used = true;
        // alp phi = eta - c M/(2r): the paper's lapse stores a regular eta (c = 0), lapse_komar its
        // regular part eta~ and c; only these smooth fields are interpolated, the pole is exact.
        if (file.has_dataset("/variables/eta") || !file.has_dataset("/variables/eta_regular")) {
          eta_ = need("/variables/eta", "alp = eta/phi at a puncture (or /variables/eta_regular with /scalars@lapse_komar_c)");
        } else {
          eta_ = need("/variables/eta_regular", "alp = (eta~ - c M/(2r))/phi at a puncture");
          const std::optional<double> c = file.scalar("lapse_komar_c");
          if (!c) throw Error(BHNSID_READER_ERR_FORMAT, file.path() + " has /variables/eta_regular but no /scalars@lapse_komar_c");
          lapse_strength_ = *c;
        }
      } else {
        it.data = need("/ADMBase/alp", "alp");
      }
    } else if (name == "betax" || name == "betay" || name == "betaz") {
      it.kind = Kind::shift;
      it.component = name[4] - 'x';
      it.data = optional("/ADMBase/" + name);  // absent: beta = 0
    } else if (name.size() == 3 && (name[0] == 'g' || name[0] == 'k') && tensor_index(name.substr(1)) >= 0) {
      it.component = tensor_index(name.substr(1));
      if (name[0] == 'g') {
        it.kind = Kind::metric;
        metric_used = true;
      } else {
        it.kind = Kind::curvature;
        it.data = optional("/ADMBase/" + name);  // absent: K_ij = 0
      }
    } else if (name == "rho" || name == "press" || name == "eps") {
      it.kind = name == "rho" ? Kind::rho : name == "press" ? Kind::press : Kind::eps;
      fluid_used = true;
      if (it.kind != Kind::rho && file.has_dataset("/HydroBase/rho") && !file.eos())
        throw Error(BHNSID_READER_ERR_EOS, "cannot compute " + name + ": " + file.eos_problem() + " (rho is available)");
    } else if (name == "vel[0]" || name == "vel[1]" || name == "vel[2]") {
      it.kind = Kind::vel;
      it.component = name[4] - '0';
      fluid_used = true;
    } else if (name == "w_lorentz") {
      it.kind = Kind::w_lorentz;
      fluid_used = true;
      metric_used = true;
    } else {
      std::string known;
      for (const std::string& n : etk_field_names()) known += (known.empty() ? "" : " ") + n;
      throw Error(BHNSID_READER_ERR_ARGUMENT,
                  "unknown field '" + name + "' (known: " + known + ", or a dataset path such as /variables/chi)");
    }
    items_.push_back(it);
  }
  if (fluid_used && file.has_dataset("/HydroBase/rho")) {
    rho_ = check_only ? nullptr : &file.field("/HydroBase/rho");
    for (int c = 0; c < 3; ++c)
      vel_[static_cast<std::size_t>(c)] =
          need("/HydroBase/vel[" + std::to_string(c) + "]", "the fluid (HydroBase/rho is present)");
  }
  if (metric_used) {
    if (puncture_) {
      chi_ = need("/variables/chi", "the metric at a puncture (phi = M/2r + chi)");
      bh_mass_ = *mass;
      const char* pos[3] = {"bh_position_x", "bh_position_y", "bh_position_z"};
      for (int a = 0; a < 3; ++a) {
        const std::optional<double> v = file.scalar(pos[a]);
        if (!v) throw Error(BHNSID_READER_ERR_FORMAT, file.path() + " has bh_bare_mass but no /scalars@" + pos[a]);
        bh_position_[static_cast<std::size_t>(a)] = *v;
      }
    } else {
      for (int c = 0; c < 6; ++c)
        metric_[static_cast<std::size_t>(c)] = need(std::string("/ADMBase/g") + metric_suffix[c], "the metric");
    }
  }
}

void Request::metric(const Stencil& s, std::size_t index, Point& p) const {
  if (p.have_metric) return;
  if (puncture_) {
    const double dx = s.point[0] - bh_position_[0], dy = s.point[1] - bh_position_[1], dz = s.point[2] - bh_position_[2];
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    p.pole = bh_mass_ / (2 * r);
    p.phi = p.pole + interpolate(file_.grid(), *chi_, s);
    const double g = std::pow(p.phi, 4);
    if (r == 0 || (p.phi > 0 && !std::isfinite(g) && !s.extrapolated))
      throw Error(BHNSID_READER_ERR_PUNCTURE, point_text(index, s) + " is at the puncture, where the metric is infinite");
    if (!std::isfinite(g) || !(p.phi > 0)) {
      // Far outside the box the edge polynomial of chi runs away: the point is too far to
      // extrapolate to, which is not the puncture's doing.
      std::ostringstream m;
      m.precision(17);
      m << point_text(index, s) << ": the conformal factor phi = M/(2r) + chi = " << p.phi << " is not a positive number";
      if (s.extrapolated)
        throw Error(BHNSID_READER_ERR_OUTSIDE, m.str() + " there: the point lies too far outside the grid for " +
                                                   "chi to be extrapolated (clamp it, or keep it near the grid)");
      throw Error(BHNSID_READER_ERR_VALUE, m.str() + " (/variables/chi is too negative there)");
    }
    p.g = {g, 0, 0, g, 0, g};
  } else {
    for (std::size_t c = 0; c < 6; ++c) p.g[c] = interpolate(file_.grid(), *metric_[c], s);
  }
  p.have_metric = true;
}

double Request::density(const Stencil& s, Point& p) const {
  if (!p.have_rho) {
    // Interpolation overshoots below zero just outside the surface; the matter is then vacuum.
    p.rho = rho_ ? std::max(0.0, interpolate(file_.grid(), *rho_, s)) : 0.0;
    p.have_rho = true;
  }
  return p.rho;
}

void Request::evaluate(const Stencil& s, std::size_t index, double* out) const {
  Point p;
  const Grid& g = file_.grid();
  for (std::size_t f = 0; f < items_.size(); ++f) {
    const Item& it = items_[f];
    double v = 0;
    switch (it.kind) {
      case Kind::raw:
      case Kind::shift:
      case Kind::curvature:
        v = it.data ? interpolate(g, *it.data, s) : 0.0;
        break;
      case Kind::lapse:
        if (puncture_) {
          metric(s, index, p);
          v = (interpolate(g, *eta_, s) - lapse_strength_ * p.pole) / p.phi;
        } else {
          v = interpolate(g, *it.data, s);
        }
        break;
      case Kind::metric:
        metric(s, index, p);
        v = p.g[static_cast<std::size_t>(it.component)];
        break;
      case Kind::rho:
        v = density(s, p);
        break;
      case Kind::press:
      case Kind::eps: {
        const double rho = density(s, p);
        double press = 0, eps = 0;
        if (rho > 0) eos_at(*file_.eos(), rho, press, eps);
        v = it.kind == Kind::press ? press : eps;
        break;
      }
      case Kind::vel:
        v = density(s, p) > 0 ? interpolate(g, *vel_[static_cast<std::size_t>(it.component)], s) : 0.0;
        break;
      case Kind::w_lorentz: {
        if (density(s, p) == 0) {
          v = 1;
          break;
        }
        metric(s, index, p);
        double vv[3];
        for (std::size_t c = 0; c < 3; ++c) vv[c] = interpolate(g, *vel_[c], s);
        double v2 = 0;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) v2 += p.g[static_cast<std::size_t>(sym[a][b])] * vv[a] * vv[b];
        if (!(v2 < 1))
          throw Error(BHNSID_READER_ERR_VALUE,
                      point_text(index, s) + ": the interpolated velocity has gamma_ij v^i v^j = " + std::to_string(v2) +
                          " >= 1, no Lorentz factor");
        v = 1 / std::sqrt(1 - v2);
        break;
      }
    }
    // A polynomial evaluated far outside the box overflows: say so rather than return inf or nan.
    if (s.extrapolated && !std::isfinite(v))
      throw Error(BHNSID_READER_ERR_OUTSIDE, point_text(index, s) + ": " + it.name +
                                                 " is not finite there: the point lies too far outside the grid to "
                                                 "extrapolate to (clamp it, or keep it near the grid)");
    out[f] = v;
  }
}

}  // namespace bhnsid::reader
