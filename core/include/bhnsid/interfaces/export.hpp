#pragma once
// Physical fields for the output plugins, in the Einstein Toolkit's names and conventions
// (ADMBase, HydroBase), published by the plugin that owns each quantity under a capability
// "export.<plugin>": the lapse plugin knows alp = eta/phi, the star the Valencia velocity,
// and an output plugin writes whatever is published without knowing any of it.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bhnsid/core/services.hpp"
#include "bhnsid/interfaces/grid.hpp"

namespace bhnsid {

struct ExportField {
  std::string group;  ///< the Einstein Toolkit thorn whose variable this is: "ADMBase", "HydroBase"
  std::string name;   ///< its name there: "alp", "gxx", "vel[0]"
  std::string units;  ///< G = c = 1 with the EOS's units: "1", "1/length", "mass/length^3"
  Parity parity;      ///< sign under z -> -z (equatorial symmetry)
  std::string doc;    ///< what it is, in one line, with the paper's symbols
  /// When set, this field equals the earlier field of that name in the same group (gyy = gxx under
  /// conformal flatness): its fill is not called and an output may store it once (a link).
  std::string same_as = {};
};

class FieldExport : public core::Service {
 public:
  ~FieldExport() override;  ///< defined in the core library (see grid.hpp)
  virtual std::vector<ExportField> export_fields() const = 0;
  /// Fills `out` (Level::size doubles in the finest level's layout; only stored points are read)
  /// with the physical value of export_fields()[index] at every stored point of the finest level,
  /// in physical units (x = sigma xhat): finite everywhere, the puncture, the excision cube and the
  /// vacuum outside the star included.
  virtual void fill(std::size_t index, double* out) const = 0;
  /// The region, in physical coordinates, where export_fields()[index] holds a set value rather
  /// than a solution (the shift's excision cube): a reader may fill it smoothly instead.
  virtual std::optional<ExcisionRegion> held_region(std::size_t /*index*/) const { return std::nullopt; }
};

/// A FieldExport made of fields and one fill function each: what a plugin exporting a few fields needs.
class FieldExportList final : public FieldExport {
 public:
  using Fill = std::function<void(double* out)>;
  using Held = std::function<std::optional<ExcisionRegion>()>;
  void add(ExportField field, Fill fill, Held held = {}) {
    fields_.push_back(std::move(field));
    fills_.push_back(std::move(fill));
    helds_.push_back(std::move(held));
  }
  std::vector<ExportField> export_fields() const override { return fields_; }
  void fill(std::size_t index, double* out) const override { fills_.at(index)(out); }
  std::optional<ExcisionRegion> held_region(std::size_t index) const override {
    const Held& h = helds_.at(index);
    return h ? h() : std::nullopt;
  }

 private:
  std::vector<ExportField> fields_;
  std::vector<Fill> fills_;
  std::vector<Held> helds_;
};

}  // namespace bhnsid
