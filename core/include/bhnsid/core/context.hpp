#pragma once
// What a scheduled function sees: its own parameters, the services, the log, the run directory
// and the scalars that end up in summary.json. One Context per active plugin.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bhnsid/core/log.hpp"
#include "bhnsid/core/params.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/core/services.hpp"

namespace bhnsid::core {

struct RunState;

/// What the core knows of the run, for an output plugin that records it beside the fields.
struct RunRecord {
  std::string parameter_file;       ///< the input file's text as read (the --set overrides are in the next)
  std::string resolved_parameters;  ///< params.yaml: every value, which reproduces the run
  std::vector<std::pair<std::string, std::string>> provenance;  ///< version, git_revision, ... as in summary.json
  std::vector<std::pair<std::string, double>> scalars;          ///< every scalar set so far
  std::string failure;  ///< empty unless the run has failed so far (OUTPUT also runs after a failure)
  bool initial_data = false;  ///< INITIAL completed: there is a state (OUTPUT also runs after an early signal)
  std::vector<std::pair<std::string, std::string>> implementations;  ///< (capability, active plugin)
};

class Context {
 public:
  Context(RunState& state, const PluginDecl& decl);

  const std::string& plugin() const { return decl_->name; }
  /// This plugin's own section.
  const ParamSection& params() const;
  /// Another active plugin's section, or "run" for the core's; read-only sharing.
  const ParamSection& params(const std::string& section) const;

  const Log& log() const { return log_; }
  const Services& services() const;

  /// Publish a service under a capability this plugin declared in `implements`.
  template <class T>
  void publish(const std::string& capability, std::shared_ptr<T> service) {
    publish_raw(capability, std::static_pointer_cast<Service>(std::move(service)));
  }

  /// A number for summary.json "scalars"; set during the loop it is also recorded per iteration.
  void set_scalar(const std::string& name, double value);
  /// set_scalar(), and the value joins the core's one terminal line per loop iteration (the
  /// quantities a user watches converge).
  void show_progress(const std::string& name, double value);
  /// Current loop iteration (1-based), 0 before the loop.
  int iteration() const;
  /// The fraction of its full step an UPDATE entry takes: 1, or 1/2^m when this iteration's SOLVE
  /// failed m times with a StepFailure and RETREAT undid the previous update each time.
  double step_fraction() const;
  /// run.max_retreats: 0 when no SOLVE failure is ever retreated from (a plugin then keeps no
  /// state for RETREAT).
  int max_retreats() const;
  /// The run directory; empty for `bhnsid check` and `schedule`.
  const std::filesystem::path& run_directory() const;
  /// Writes run_directory()/relative_name atomically (temporary name, fsync, rename).
  void write_output(const std::string& relative_name, const std::string& contents) const;
  /// For an output that a library writes through a path (HDF5): records `relative_name` and its
  /// temporary `relative_name.partial` as this run's and returns the temporary's path; commit_output
  /// fsyncs it and renames it into place, abandon_output removes it (after a failed write).
  std::filesystem::path begin_output(const std::string& relative_name) const;
  void commit_output(const std::string& relative_name) const;
  void abandon_output(const std::string& relative_name) const;
  RunRecord run_record() const;
  /// Every variable declared by an active plugin, in plugin order.
  const std::vector<VariableSpec>& variables() const;

 private:
  void publish_raw(const std::string& capability, std::shared_ptr<Service> service);
  RunState* state_;
  const PluginDecl* decl_;
  Log log_;
};

}  // namespace bhnsid::core
