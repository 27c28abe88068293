#pragma once
// A parameter as a plugin declares it: type, default or required-with-example, range, doc.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace bhnsid::core {

enum class ParamType { boolean, integer, real, string, keyword, real_vector };

/// A resolved value; keywords are held as strings.
using ParamValue = std::variant<bool, std::int64_t, double, std::string, std::vector<double>>;

/// How a parameter changes from one resolution to the next in a convergence series (bhnsid
/// validate): a plugin declares it, so that the core refines a configuration without knowing its
/// plugins. doubles: the value times 2 per halving of the spacing (a point count, a width in
/// points); halves: the value divided by 2 (a spacing).
enum class Refinement { none, doubles, halves };

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::real;
  std::string doc;
  std::optional<ParamValue> default_value;  ///< absent: the parameter is required
  std::optional<ParamValue> example;        ///< shown for required parameters by `params --yaml`
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;  ///< true: value must be > min rather than >= min
  bool max_open = false;
  std::vector<std::string> keywords;  ///< allowed values of a keyword parameter
  int length = -1;                    ///< required length of a real vector, -1 for any
  bool steerable = false;             ///< may change between the runs of a sequence
  Refinement refinement = Refinement::none;  ///< how a convergence series changes it

  bool required() const { return !default_value.has_value(); }
};

const char* to_string(ParamType type);
/// "[0, inf)", "(0, 1]", "one of none|equatorial", "3 reals" ... for docs and errors.
std::string describe_range(const ParamSpec& spec);
/// YAML flow text of a value ("0.03", "true", "[0, 0.3, 0]", "equatorial").
std::string format_value(const ParamValue& value);
/// Empty when the value satisfies the spec's type and range, otherwise what was expected.
std::string check_value(const ParamSpec& spec, const ParamValue& value);

}  // namespace bhnsid::core
