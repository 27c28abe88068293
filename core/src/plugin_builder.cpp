#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <stdexcept>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"

namespace bhnsid::core {

const ParamSpec* PluginDecl::find_param(const std::string& key) const {
  for (const auto& p : params)
    if (p.name == key) return &p;
  return nullptr;
}

ParamSpec& ParamHandle::spec() { return decl_->params[index_]; }
ParamHandle& ParamHandle::doc(std::string text) { spec().doc = std::move(text); return *this; }
ParamHandle& ParamHandle::default_value(ParamValue value) {
  // Integer literals for real parameters are a convenience, not a type error.
  if (spec().type == ParamType::real && std::holds_alternative<std::int64_t>(value))
    value = static_cast<double>(std::get<std::int64_t>(value));
  spec().default_value = std::move(value);
  return *this;
}
ParamHandle& ParamHandle::required(ParamValue example) {
  spec().default_value.reset();
  spec().example = std::move(example);
  return *this;
}
ParamHandle& ParamHandle::at_least(double lo) { spec().min = lo; spec().min_open = false; return *this; }
ParamHandle& ParamHandle::greater_than(double lo) { spec().min = lo; spec().min_open = true; return *this; }
ParamHandle& ParamHandle::at_most(double hi) { spec().max = hi; spec().max_open = false; return *this; }
ParamHandle& ParamHandle::less_than(double hi) { spec().max = hi; spec().max_open = true; return *this; }
ParamHandle& ParamHandle::length(int n) { spec().length = n; return *this; }
ParamHandle& ParamHandle::steerable() { spec().steerable = true; return *this; }
ParamHandle& ParamHandle::refines(Refinement how) {
  if (spec().type != ParamType::integer && spec().type != ParamType::real)
    throw std::logic_error("ParamHandle::refines: only integer and real parameters follow the spacing");
  spec().refinement = how;
  return *this;
}

ScheduleHandle& ScheduleHandle::doc(std::string text) { decl_->schedule[index_].doc = std::move(text); return *this; }
ScheduleHandle& ScheduleHandle::before(std::string reference) {
  decl_->schedule[index_].before.push_back({std::move(reference), false});
  return *this;
}
ScheduleHandle& ScheduleHandle::after(std::string reference) {
  decl_->schedule[index_].after.push_back({std::move(reference), false});
  return *this;
}
ScheduleHandle& ScheduleHandle::before_if_present(std::string reference) {
  decl_->schedule[index_].before.push_back({std::move(reference), true});
  return *this;
}
ScheduleHandle& ScheduleHandle::after_if_present(std::string reference) {
  decl_->schedule[index_].after.push_back({std::move(reference), true});
  return *this;
}

void PluginBuilder::implements(std::string capability) { decl_.implements.push_back(std::move(capability)); }
void PluginBuilder::require(std::string capability) { decl_.requires_caps.push_back(std::move(capability)); }

ParamHandle PluginBuilder::add_param(std::string name, ParamType type) {
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = type;
  decl_.params.push_back(std::move(spec));
  return ParamHandle(decl_, decl_.params.size() - 1);
}
ParamHandle PluginBuilder::boolean(std::string name) { return add_param(std::move(name), ParamType::boolean); }
ParamHandle PluginBuilder::integer(std::string name) { return add_param(std::move(name), ParamType::integer); }
ParamHandle PluginBuilder::real(std::string name) { return add_param(std::move(name), ParamType::real); }
ParamHandle PluginBuilder::string(std::string name) { return add_param(std::move(name), ParamType::string); }
ParamHandle PluginBuilder::real_vector(std::string name) { return add_param(std::move(name), ParamType::real_vector); }
ParamHandle PluginBuilder::keyword(std::string name, std::vector<std::string> allowed) {
  ParamHandle handle = add_param(std::move(name), ParamType::keyword);
  decl_.params.back().keywords = std::move(allowed);
  return handle;
}

void PluginBuilder::variable(VariableSpec spec) {
  spec.plugin = decl_.name;
  decl_.variables.push_back(std::move(spec));
}

ScheduleHandle PluginBuilder::schedule(Bin bin, std::string name, ScheduledFn fn) {
  ScheduleEntry entry;
  entry.plugin = decl_.name;
  entry.name = std::move(name);
  entry.bin = bin;
  entry.fn = std::move(fn);
  decl_.schedule.push_back(std::move(entry));
  return ScheduleHandle(decl_, decl_.schedule.size() - 1);
}

ScheduleHandle PluginBuilder::check(std::string name, CheckFn fn) {
  ScheduleEntry entry;
  entry.plugin = decl_.name;
  entry.name = std::move(name);
  entry.bin = Bin::check;
  entry.check = std::move(fn);
  decl_.schedule.push_back(std::move(entry));
  return ScheduleHandle(decl_, decl_.schedule.size() - 1);
}

void PluginBuilder::memory(MemoryFn fn, MemoryStage stage) { decl_.memory.push_back(MemoryEstimator{stage, std::move(fn)}); }

void PluginBuilder::checkpoint(CheckpointSaveFn save, CheckpointRestoreFn restore) {
  decl_.checkpoint_save = std::move(save);
  decl_.checkpoint_restore = std::move(restore);
}

void PluginBuilder::warm_start(CheckpointRestoreFn fn) { decl_.warm_start = std::move(fn); }

namespace {
bool is_identifier(const std::string& s) {
  if (s.empty() || !std::islower(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_';
  });
}

// Capabilities may be grouped by dots ("equation.hamiltonian"), each part an identifier.
bool is_capability_name(const std::string& s) {
  std::size_t start = 0;
  for (;;) {
    const std::size_t dot = s.find('.', start);
    if (!is_identifier(s.substr(start, dot == std::string::npos ? std::string::npos : dot - start))) return false;
    if (dot == std::string::npos) return true;
    start = dot + 1;
  }
}
}  // namespace

void validate_declaration(const PluginDecl& decl) {
  const auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("plugin '{}' declares {}", decl.name, what));
  };
  std::set<std::string> seen;
  for (const auto& p : decl.params) {
    if (!is_identifier(p.name)) fail(fmt::format("a parameter named '{}' (expected lower case, digits, '_')", p.name));
    if (!seen.insert(p.name).second) fail(fmt::format("parameter '{}' twice", p.name));
    if (p.doc.empty()) fail(fmt::format("parameter '{}' without a doc", p.name));
    if (p.type == ParamType::keyword && p.keywords.empty()) fail(fmt::format("keyword '{}' with no allowed values", p.name));
    if (p.default_value) {
      const std::string problem = check_value(p, *p.default_value);
      if (!problem.empty()) fail(fmt::format("a default for '{}' that is not {}", p.name, problem));
    } else {
      if (!p.example) fail(fmt::format("required parameter '{}' without an example value", p.name));
      const std::string problem = check_value(p, *p.example);
      if (!problem.empty()) fail(fmt::format("an example for '{}' that is not {}", p.name, problem));
    }
  }
  seen.clear();
  for (const auto& v : decl.variables) {
    if (!is_identifier(v.name)) fail(fmt::format("a variable named '{}'", v.name));
    if (!seen.insert(v.name).second) fail(fmt::format("variable '{}' twice", v.name));
  }
  seen.clear();
  for (const auto& e : decl.schedule) {
    if (!is_identifier(e.name)) fail(fmt::format("a schedule entry named '{}'", e.name));
    if (!seen.insert(e.name).second) fail(fmt::format("schedule entry '{}' twice", e.name));
    if (e.bin == Bin::check ? !e.check : !e.fn) fail(fmt::format("schedule entry '{}' without a function", e.name));
    for (const auto* refs : {&e.before, &e.after})
      for (const auto& r : *refs) {
        const std::size_t dot = r.target.rfind('.');
        if (dot == std::string::npos || !is_capability_name(r.target.substr(0, dot)) ||
            !is_identifier(r.target.substr(dot + 1)))
          fail(fmt::format("schedule entry '{}' ordered against '{}' (expected 'capability.entry', e.g. 'lapse.setup')",
                           e.name, r.target));
      }
  }
  for (const auto& m : decl.memory)
    if (!m.fn) fail("a memory estimate without a function");
  for (const auto& c : decl.implements)
    if (!is_capability_name(c)) fail(fmt::format("a capability named '{}'", c));
  for (const auto& c : decl.requires_caps)
    if (!is_capability_name(c)) fail(fmt::format("a required capability named '{}'", c));
}

}  // namespace bhnsid::core
