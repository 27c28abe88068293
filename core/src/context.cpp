#include "bhnsid/core/context.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>

#include "bhnsid/core/atomic_file.hpp"
#include "bhnsid/core/owned_entry.hpp"
#include "run_state.hpp"

namespace bhnsid::core {

Context::Context(RunState& state, const PluginDecl& decl) : state_(&state), decl_(&decl), log_(&state.sink, decl.name) {}

const ParamSection& Context::params() const { return state_->config.params.at(decl_->name); }

const ParamSection& Context::params(const std::string& section) const {
  auto it = state_->config.params.find(section);
  if (it == state_->config.params.end())
    throw std::logic_error(fmt::format("plugin '{}' reads section '{}', which is not active", decl_->name, section));
  return it->second;
}

const Services& Context::services() const { return state_->services; }

void Context::publish_raw(const std::string& capability, std::shared_ptr<Service> service) {
  if (std::find(decl_->implements.begin(), decl_->implements.end(), capability) == decl_->implements.end())
    throw std::logic_error(fmt::format("plugin '{}' publishes service '{}' without declaring that it implements it",
                                       decl_->name, capability));
  state_->services.publish_raw(decl_->name, capability, std::move(service));
}

namespace {
// Sets `name` in an ordered list of (name, value): first set, first listed.
void set_in(std::vector<std::pair<std::string, double>>& list, const std::string& name, double value) {
  auto it = std::find_if(list.begin(), list.end(), [&](const auto& s) { return s.first == name; });
  if (it == list.end())
    list.emplace_back(name, value);
  else
    it->second = value;
}
}  // namespace

void Context::set_scalar(const std::string& name, double value) {
  set_in(state_->scalars, name, value);
  if (state_->in_loop && !state_->history.empty()) {
    auto& columns = state_->history_columns;
    if (std::find(columns.begin(), columns.end(), name) == columns.end()) columns.push_back(name);
    state_->history.back()[name] = value;
  }
}

void Context::show_progress(const std::string& name, double value) {
  set_scalar(name, value);
  set_in(state_->progress, name, value);
}

int Context::iteration() const { return state_->iteration; }
double Context::step_fraction() const { return state_->step_fraction; }
int Context::max_retreats() const {
  const auto it = state_->config.params.find("run");
  return it == state_->config.params.end() ? 0 : static_cast<int>(it->second.integer("max_retreats"));
}
const std::filesystem::path& Context::run_directory() const { return state_->run_dir; }

void Context::write_output(const std::string& relative_name, const std::string& contents) const {
  const std::filesystem::path name = std::filesystem::path(relative_name).lexically_normal();
  if (name.empty() || name.is_absolute() || *name.begin() == ".." || *name.begin() == "." || !name.has_filename())
    throw std::logic_error(fmt::format("plugin '{}' writes '{}': expected a file name inside the run directory",
                                       decl_->name, relative_name));
  if (state_->directory) state_->directory->record(name.begin()->string());
  write_file_atomic(state_->run_dir / relative_name, contents);
}

namespace {

std::filesystem::path checked_output_name(const std::string& plugin, const std::string& relative_name) {
  const std::filesystem::path name = std::filesystem::path(relative_name).lexically_normal();
  if (name.empty() || name.is_absolute() || *name.begin() == ".." || *name.begin() == "." || !name.has_filename() ||
      name.has_parent_path())
    throw std::logic_error(fmt::format("plugin '{}' writes '{}': expected a file name in the run directory", plugin,
                                       relative_name));
  return name;
}

}  // namespace

std::filesystem::path Context::begin_output(const std::string& relative_name) const {
  const std::filesystem::path name = checked_output_name(decl_->name, relative_name);
  if (state_->directory) {
    state_->directory->record(name.string());
    state_->directory->record(name.string() + ".partial");
  }
  // Created here, new, so that the plugin's writer (HDF5 opens by path and truncates) never writes
  // through a symbolic link or into another file's inode left at that name.
  const std::filesystem::path partial = state_->run_dir / (name.string() + ".partial");
  ::close(create_fresh_file(partial));
  return partial;
}

void Context::commit_output(const std::string& relative_name) const {
  const std::filesystem::path name = checked_output_name(decl_->name, relative_name);
  commit_file(state_->run_dir / (name.string() + ".partial"), state_->run_dir / name);
}

void Context::abandon_output(const std::string& relative_name) const {
  std::error_code ignored;
  std::filesystem::remove(state_->run_dir / (checked_output_name(decl_->name, relative_name).string() + ".partial"), ignored);
}

const std::vector<VariableSpec>& Context::variables() const { return state_->config.variables; }

RunRecord Context::run_record() const {
  RunRecord r;
  r.parameter_file = state_->config.file.text;
  r.resolved_parameters = state_->resolved_parameters;
  r.provenance = state_->provenance;
  r.scalars = state_->scalars;
  r.failure = state_->failure;
  r.initial_data = state_->initial_data;
  for (const PluginDecl* decl : state_->config.decls)
    for (const std::string& capability : decl->implements) r.implementations.emplace_back(capability, decl->name);
  return r;
}

}  // namespace bhnsid::core
