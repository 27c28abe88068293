#include "bhnsid/core/param_spec.hpp"

#include <fmt/format.h>

#include <cmath>

namespace bhnsid::core {

const char* to_string(ParamType type) {
  switch (type) {
    case ParamType::boolean: return "bool";
    case ParamType::integer: return "int";
    case ParamType::real: return "real";
    case ParamType::string: return "string";
    case ParamType::keyword: return "keyword";
    case ParamType::real_vector: return "real vector";
  }
  return "?";
}

namespace {
std::string bound(double x) {
  if (std::isinf(x)) return x < 0 ? "-inf" : "inf";
  return fmt::format("{}", x);
}

std::string join(const std::vector<std::string>& words, const char* separator) {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : separator) + w;
  return out;
}

bool in_range(const ParamSpec& spec, double x) {
  if (spec.min_open ? !(x > spec.min) : !(x >= spec.min)) return false;
  if (spec.max_open ? !(x < spec.max) : !(x <= spec.max)) return false;
  return true;
}

bool has_range(const ParamSpec& spec) { return !std::isinf(spec.min) || !std::isinf(spec.max); }
}  // namespace

std::string describe_range(const ParamSpec& spec) {
  switch (spec.type) {
    case ParamType::boolean: return "true|false";
    case ParamType::string: return "any text";
    case ParamType::keyword: return "one of " + join(spec.keywords, "|");
    case ParamType::integer:
    case ParamType::real:
    case ParamType::real_vector: {
      std::string text;
      if (has_range(spec))
        text = fmt::format("{}{}, {}{}", spec.min_open || std::isinf(spec.min) ? "(" : "[", bound(spec.min),
                           bound(spec.max), spec.max_open || std::isinf(spec.max) ? ")" : "]");
      else
        text = spec.type == ParamType::integer ? "any integer" : "any finite real";
      if (spec.type == ParamType::real_vector)
        text = (spec.length >= 0 ? fmt::format("{} reals", spec.length) : std::string("reals")) +
               (has_range(spec) ? ", each in " + text : std::string{});
      return text;
    }
  }
  return "?";
}

std::string format_value(const ParamValue& value) {
  struct Visitor {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(std::int64_t i) const { return fmt::format("{}", i); }
    std::string operator()(double x) const {
      std::string s = fmt::format("{}", x);
      // Keep reals recognisable as reals when the file is read back.
      if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
      return s;
    }
    std::string operator()(const std::string& s) const {
      const bool plain = !s.empty() && s.find_first_of(":#[]{},&*!|>'\"%@`\n") == std::string::npos &&
                         s.front() != ' ' && s.back() != ' ' && s.front() != '-' && s.front() != '?';
      if (plain) return s;
      std::string quoted = "\"";
      for (char c : s) quoted += (c == '"' || c == '\\') ? std::string("\\") + c : (c == '\n' ? std::string("\\n") : std::string(1, c));
      return quoted + "\"";
    }
    std::string operator()(const std::vector<double>& v) const {
      std::string s = "[";
      for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + (*this)(v[i]);
      return s + "]";
    }
  };
  return std::visit(Visitor{}, value);
}

std::string check_value(const ParamSpec& spec, const ParamValue& value) {
  const auto range_message = [&] {
    return std::string(spec.type == ParamType::integer ? "an integer" : "a real") + " in " + describe_range(spec);
  };
  switch (spec.type) {
    case ParamType::boolean:
      return std::holds_alternative<bool>(value) ? "" : "true or false";
    case ParamType::integer: {
      if (!std::holds_alternative<std::int64_t>(value)) return "an integer";
      return in_range(spec, static_cast<double>(std::get<std::int64_t>(value))) ? "" : range_message();
    }
    case ParamType::real: {
      if (!std::holds_alternative<double>(value)) return "a real";
      const double x = std::get<double>(value);
      if (!std::isfinite(x)) return "a finite real";
      return in_range(spec, x) ? "" : range_message();
    }
    case ParamType::string:
      return std::holds_alternative<std::string>(value) ? "" : "a string";
    case ParamType::keyword: {
      if (!std::holds_alternative<std::string>(value)) return describe_range(spec);
      for (const auto& k : spec.keywords)
        if (k == std::get<std::string>(value)) return "";
      return describe_range(spec);
    }
    case ParamType::real_vector: {
      if (!std::holds_alternative<std::vector<double>>(value)) return "a list of reals";
      const auto& v = std::get<std::vector<double>>(value);
      if (spec.length >= 0 && static_cast<int>(v.size()) != spec.length)
        return fmt::format("a list of exactly {} reals", spec.length);
      for (double x : v)
        if (!std::isfinite(x) || !in_range(spec, x)) return "a list of " + describe_range(spec);
      return "";
    }
  }
  return "?";
}

}  // namespace bhnsid::core
