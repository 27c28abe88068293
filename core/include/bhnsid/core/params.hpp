#pragma once
// Resolved parameters, read by plugins through typed accessors. A wrong name or type here is a
// plugin bug (the parameter file was validated long before), so it throws std::logic_error.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "bhnsid/core/param_spec.hpp"

namespace bhnsid::core {

/// The resolved values of one section (one plugin, or the core's `run` section).
class ParamSection {
 public:
  ParamSection() = default;
  ParamSection(std::string name, std::map<std::string, ParamValue> values)
      : name_(std::move(name)), values_(std::move(values)) {}

  bool boolean(const std::string& key) const;
  std::int64_t integer(const std::string& key) const;
  double real(const std::string& key) const;
  const std::string& string(const std::string& key) const;  ///< also keywords
  const std::vector<double>& real_vector(const std::string& key) const;

  const std::string& name() const { return name_; }
  const std::map<std::string, ParamValue>& values() const { return values_; }

 private:
  const ParamValue& at(const std::string& key) const;
  std::string name_;
  std::map<std::string, ParamValue> values_;
};

}  // namespace bhnsid::core
