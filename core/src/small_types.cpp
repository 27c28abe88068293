// Out-of-line definitions of the core's small value types: names for enums, error classes,
// the Service base (its key function anchors the type information in the core library).
#include <fmt/format.h>

#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/params.hpp"
#include "bhnsid/core/schedule.hpp"
#include "bhnsid/core/services.hpp"
#include "bhnsid/core/variables.hpp"

namespace bhnsid::core {

InputError::InputError(const std::string& what) : std::runtime_error(what) {}
InputError::~InputError() = default;
RunFailure::RunFailure(const std::string& what) : std::runtime_error(what) {}
RunFailure::~RunFailure() = default;
StepFailure::StepFailure(const std::string& what) : RunFailure(what) {}
StepFailure::~StepFailure() = default;
Interrupted::Interrupted(const std::string& what) : std::runtime_error(what) {}
Interrupted::~Interrupted() = default;

Service::~Service() = default;

const char* to_string(Bin bin) {
  switch (bin) {
    case Bin::startup: return "STARTUP";
    case Bin::paramcheck: return "PARAMCHECK";
    case Bin::setup: return "SETUP";
    case Bin::initial: return "INITIAL";
    case Bin::solve: return "SOLVE";
    case Bin::update: return "UPDATE";
    case Bin::check: return "CHECK";
    case Bin::retreat: return "RETREAT";
    case Bin::analysis: return "ANALYSIS";
    case Bin::output: return "OUTPUT";
    case Bin::terminate: return "TERMINATE";
  }
  return "?";
}

bool in_loop(Bin bin) { return bin == Bin::solve || bin == Bin::update || bin == Bin::check || bin == Bin::retreat; }

const std::vector<Bin>& all_bins() {
  static const std::vector<Bin> bins{Bin::paramcheck, Bin::startup, Bin::setup,   Bin::initial,  Bin::solve, Bin::update,
                                     Bin::check,      Bin::retreat, Bin::analysis, Bin::output, Bin::terminate};
  return bins;
}

const char* to_string(TensorKind kind) {
  switch (kind) {
    case TensorKind::scalar: return "scalar";
    case TensorKind::vector_x: return "vector_x";
    case TensorKind::vector_y: return "vector_y";
    case TensorKind::vector_z: return "vector_z";
    case TensorKind::tensor_xx: return "tensor_xx";
    case TensorKind::tensor_xy: return "tensor_xy";
    case TensorKind::tensor_xz: return "tensor_xz";
    case TensorKind::tensor_yy: return "tensor_yy";
    case TensorKind::tensor_yz: return "tensor_yz";
    case TensorKind::tensor_zz: return "tensor_zz";
  }
  return "?";
}

const char* to_string(Storage storage) {
  switch (storage) {
    case Storage::all_levels: return "all levels";
    case Storage::finest_only: return "finest only";
    case Storage::coarse_levels: return "coarse levels";
  }
  return "?";
}

int reflection_parity(TensorKind kind, int axis) {
  // Index counts along x, y, z for each kind.
  static const int counts[][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0},
                                  {1, 1, 0}, {1, 0, 1}, {0, 2, 0}, {0, 1, 1}, {0, 0, 2}};
  return counts[static_cast<int>(kind)][axis] % 2 ? -1 : 1;
}

const ParamValue& ParamSection::at(const std::string& key) const {
  auto it = values_.find(key);
  if (it == values_.end()) throw std::logic_error(fmt::format("parameter '{}.{}' is not declared", name_, key));
  return it->second;
}

namespace {
template <class T>
const T& typed(const ParamValue& value, const std::string& section, const std::string& key) {
  if (const T* v = std::get_if<T>(&value)) return *v;
  throw std::logic_error(fmt::format("parameter '{}.{}' read with the wrong type", section, key));
}
}  // namespace

bool ParamSection::boolean(const std::string& key) const { return typed<bool>(at(key), name_, key); }
std::int64_t ParamSection::integer(const std::string& key) const { return typed<std::int64_t>(at(key), name_, key); }
double ParamSection::real(const std::string& key) const { return typed<double>(at(key), name_, key); }
const std::string& ParamSection::string(const std::string& key) const { return typed<std::string>(at(key), name_, key); }
const std::vector<double>& ParamSection::real_vector(const std::string& key) const {
  return typed<std::vector<double>>(at(key), name_, key);
}

void Services::publish_raw(const std::string& plugin, const std::string& capability, std::shared_ptr<Service> service) {
  if (!service) throw std::logic_error(fmt::format("plugin '{}' published a null service '{}'", plugin, capability));
  auto [it, inserted] = entries_.emplace(capability, Entry{plugin, std::move(service)});
  if (!inserted)
    throw std::logic_error(fmt::format("plugin '{}' publishes service '{}', already published by '{}'", plugin,
                                       capability, it->second.plugin));
  order_.push_back(capability);
}

void Services::missing(const std::string& capability) const {
  if (entries_.count(capability))
    throw std::logic_error(fmt::format("service '{}' does not implement the interface asked for", capability));
  throw std::logic_error(fmt::format("no service '{}' has been published (is a plugin implementing it active and "
                                     "scheduled to publish it earlier?)",
                                     capability));
}

}  // namespace bhnsid::core
