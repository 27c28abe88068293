// Turning YAML values into typed, range-checked parameter values, section by section.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cfloat>
#include <cmath>
#include <cstdlib>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/nearest.hpp"
#include "bhnsid/core/parfile.hpp"

namespace bhnsid::core {

namespace {

std::string shown(const YamlNode& node) {
  if (node.kind != YamlNode::Kind::scalar) return node.kind_name();
  std::string text = node.scalar.size() > 40 ? node.scalar.substr(0, 40) + "..." : node.scalar;
  return "'" + text + "'";
}

[[noreturn]] void bad_value(const ParamSpec& spec, const YamlNode& node, const std::string& where,
                            const std::string& expected) {
  std::string hint;
  if (spec.type == ParamType::keyword && node.kind == YamlNode::Kind::scalar)
    hint = did_you_mean(node.scalar, spec.keywords);
  throw InputError(fmt::format("{}: {}: expected {}, got {}{}", node.pos.str(), where, expected, shown(node), hint));
}

bool is_non_finite_word(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.erase(0, 1);
  return s == ".nan" || s == "nan" || s == ".inf" || s == "inf" || s == "infinity";
}

// Decimal notation only: [+-] digits [. digits] [e|E [+-] digits], with digits on at least one
// side of the point. strtod alone would also take hexadecimal (0x10, 0x1p-3) and leading spaces.
bool is_decimal_real(const std::string& s) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t start = i;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
    return i - start;
  };
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  std::size_t mantissa = digits();
  if (i < s.size() && s[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == s.size();
}

// True when the written mantissa has a non-zero digit, i.e. the value the user meant is not 0.
bool names_non_zero(const std::string& s) {
  for (char c : s) {
    if (c == 'e' || c == 'E') break;
    if (c >= '1' && c <= '9') return true;
  }
  return false;
}

double to_real(const ParamSpec& spec, const YamlNode& node, const std::string& where) {
  if (node.kind != YamlNode::Kind::scalar || !node.plain) bad_value(spec, node, where, "a real number");
  if (is_non_finite_word(node.scalar)) bad_value(spec, node, where, "a finite real (NaN and inf are not allowed)");
  if (!is_decimal_real(node.scalar)) bad_value(spec, node, where, "a real number in decimal notation, e.g. 0.25 or 1e-3");
  const double x = std::strtod(node.scalar.c_str(), nullptr);
  if (!std::isfinite(x)) bad_value(spec, node, where, "a finite real (this overflows a double)");
  // A value below the smallest normal double would silently become 0 or lose its digits, and 0
  // can mean something else entirely (e.g. "no star").
  if (names_non_zero(node.scalar) && (x == 0 || std::fabs(x) < DBL_MIN))
    bad_value(spec, node, where, "a real whose magnitude is at least 2.2e-308 (this underflows a double)");
  return x;
}

}  // namespace

ParamValue convert_value(const ParamSpec& spec, const YamlNode& node, const std::string& where) {
  ParamValue value;
  const bool scalar = node.kind == YamlNode::Kind::scalar;
  switch (spec.type) {
    case ParamType::boolean:
      if (!scalar || !node.plain || (node.scalar != "true" && node.scalar != "false"))
        bad_value(spec, node, where, "true or false");
      value = node.scalar == "true";
      break;
    case ParamType::integer: {
      if (!scalar || !node.plain) bad_value(spec, node, where, "an integer");
      const std::string& s = node.scalar;
      const char* first = s.data() + (!s.empty() && s[0] == '+');
      std::int64_t i = 0;
      auto [ptr, ec] = std::from_chars(first, s.data() + s.size(), i);
      if (ec == std::errc::result_out_of_range) bad_value(spec, node, where, "an integer that fits in 64 bits");
      if (ec != std::errc{} || ptr != s.data() + s.size() || s.empty()) bad_value(spec, node, where, "an integer");
      value = i;
      break;
    }
    case ParamType::real:
      value = to_real(spec, node, where);
      break;
    case ParamType::string:
    case ParamType::keyword:
      if (!scalar) bad_value(spec, node, where, spec.type == ParamType::string ? "a string" : describe_range(spec));
      value = node.scalar;
      break;
    case ParamType::real_vector: {
      if (node.kind != YamlNode::Kind::sequence) bad_value(spec, node, where, "a list of reals, e.g. [0, 0.3, 0]");
      std::vector<double> v;
      for (const auto& item : node.items) v.push_back(to_real(spec, item, where));
      value = std::move(v);
      break;
    }
  }
  const std::string problem = check_value(spec, value);
  if (!problem.empty()) bad_value(spec, node, where, problem);
  return value;
}

std::map<std::string, ParamSection> resolve_params(const ParFile& file,
                                                   const std::vector<const PluginDecl*>& active,
                                                   const std::vector<std::string>& known_inactive) {
  std::vector<std::string> section_names{"plugins"};
  for (const auto* decl : active) section_names.push_back(decl->name);

  std::map<std::string, std::map<std::string, ParamValue>> given;
  for (const auto& section : file.sections) {
    auto decl_it = std::find_if(active.begin(), active.end(), [&](const PluginDecl* d) { return d->name == section.name; });
    if (decl_it == active.end()) {
      if (std::find(known_inactive.begin(), known_inactive.end(), section.name) != known_inactive.end())
        throw InputError(fmt::format(
            "{}: section '{}' sets parameters of plugin '{}', which is not in the plugins: list; add it there or "
            "remove the section (parameters of inactive plugins would be silently ignored)",
            section.pos.str(), section.name, section.name));
      throw InputError(fmt::format("{}: unknown section '{}'{}; expected 'plugins' or an active plugin's name: {}",
                                   section.pos.str(), section.name, did_you_mean(section.name, section_names),
                                   fmt::join(section_names.begin() + 1, section_names.end(), ", ")));
    }
    const PluginDecl& decl = **decl_it;
    auto& values = given[decl.name];
    for (const auto& [key, node] : section.entries) {
      const ParamSpec* spec = decl.find_param(key.scalar);
      if (!spec) {
        std::vector<std::string> keys;
        for (const auto& p : decl.params) keys.push_back(p.name);
        throw InputError(fmt::format("{}: unknown parameter '{}.{}'{}; plugin '{}' has: {}", key.pos.str(),
                                     section.name, key.scalar, did_you_mean(key.scalar, keys), decl.name,
                                     keys.empty() ? std::string("no parameters") : fmt::format("{}", fmt::join(keys, ", "))));
      }
      values[key.scalar] = convert_value(*spec, node, section.name + "." + key.scalar);
    }
  }

  std::map<std::string, ParamSection> resolved;
  for (const auto* decl : active) {
    auto& values = given[decl->name];
    for (const auto& spec : decl->params) {
      if (values.count(spec.name)) continue;
      if (spec.required())
        throw InputError(fmt::format("{}: {}.{} is required: {} ({}), e.g. {}", file.source, decl->name, spec.name,
                                     spec.doc, describe_range(spec),
                                     spec.example ? format_value(*spec.example) : std::string("?")));
      values[spec.name] = *spec.default_value;
    }
    resolved.emplace(decl->name, ParamSection(decl->name, values));
  }
  return resolved;
}

}  // namespace bhnsid::core
