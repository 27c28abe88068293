#pragma once
// The plugin contract. A plugin exports exactly one C function,
//
//   extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info();
//
// returning a plain struct whose first field is the ABI version it was built against. The loader
// checks that field before touching anything else, then calls `declare` with a PluginBuilder.
// `declare` must be cheap and side-effect free: it also runs for `bhnsid params` and `plugins`.
#include <cstdint>
#include <string>
#include <vector>

#include "bhnsid/core/checkpoint.hpp"
#include "bhnsid/core/memory.hpp"
#include "bhnsid/core/param_spec.hpp"
#include "bhnsid/core/schedule.hpp"
#include "bhnsid/core/variables.hpp"

#define BHNSID_ABI_VERSION 4u  // 2: PluginDecl gained the checkpoint functions; 3: the warm start; 4: ScheduleRef
#define BHNSID_EXPORT __attribute__((visibility("default")))

namespace bhnsid::core {

/// Everything a plugin declares; introspectable without running it.
struct PluginDecl {
  std::string name, version, description;
  std::vector<std::string> implements;
  std::vector<std::string> requires_caps;
  std::vector<ParamSpec> params;
  std::vector<VariableSpec> variables;
  std::vector<ScheduleEntry> schedule;
  std::vector<MemoryEstimator> memory;
  CheckpointSaveFn checkpoint_save;  ///< empty: the plugin keeps no state across loop iterations
  CheckpointRestoreFn checkpoint_restore;
  CheckpointRestoreFn warm_start;  ///< empty: a warm-started run keeps this plugin's INITIAL state

  const ParamSpec* find_param(const std::string& key) const;
};

class PluginBuilder;

/// Fluent handle on one declared parameter; valid only while `declare` runs.
class ParamHandle {
 public:
  ParamHandle(PluginDecl& decl, std::size_t index) : decl_(&decl), index_(index) {}
  ParamHandle& doc(std::string text);
  ParamHandle& default_value(ParamValue value);
  /// No default: the user must give it. `example` is what `bhnsid params --yaml` writes.
  ParamHandle& required(ParamValue example);
  ParamHandle& at_least(double lo);
  ParamHandle& greater_than(double lo);
  ParamHandle& at_most(double hi);
  ParamHandle& less_than(double hi);
  ParamHandle& length(int n);
  ParamHandle& steerable();
  /// How the value follows the spacing in a convergence series (integers and reals only).
  ParamHandle& refines(Refinement how);

 private:
  ParamSpec& spec();
  PluginDecl* decl_;
  std::size_t index_;
};

class ScheduleHandle {
 public:
  ScheduleHandle(PluginDecl& decl, std::size_t index) : decl_(&decl), index_(index) {}
  ScheduleHandle& doc(std::string text);
  /// Order against "capability.entry": the entry of whichever active plugin implements the
  /// capability ("lapse.setup" is the setup of the lapse in use, whichever plugin that is). Building
  /// the schedule fails, naming the reference, when no active plugin implements it or that plugin has
  /// no such entry.
  ScheduleHandle& before(std::string reference);
  ScheduleHandle& after(std::string reference);
  /// The same, for a capability the run may lack: the constraint holds only when it is present.
  ScheduleHandle& before_if_present(std::string reference);
  ScheduleHandle& after_if_present(std::string reference);

 private:
  PluginDecl* decl_;
  std::size_t index_;
};

class PluginBuilder {
 public:
  explicit PluginBuilder(PluginDecl& decl) : decl_(decl) {}

  void implements(std::string capability);
  void require(std::string capability);

  ParamHandle boolean(std::string name);
  ParamHandle integer(std::string name);
  ParamHandle real(std::string name);
  ParamHandle string(std::string name);
  ParamHandle keyword(std::string name, std::vector<std::string> allowed);
  ParamHandle real_vector(std::string name);

  void variable(VariableSpec spec);

  ScheduleHandle schedule(Bin bin, std::string name, ScheduledFn fn);
  ScheduleHandle check(std::string name, CheckFn fn);

  /// Estimates what the plugin will allocate, from parameters alone (after PARAMCHECK, so services
  /// published there, such as a grid's layout, can be read). `derived` runs after every plugin's
  /// `own` stage and sees its counts.
  void memory(MemoryFn fn, MemoryStage stage = MemoryStage::own);

  /// The state this plugin carries from one loop iteration to the next (core/checkpoint.hpp):
  /// `save` runs after every iteration, `restore` on --resume after INITIAL, before the loop goes
  /// on. A plugin without one is taken to carry none.
  void checkpoint(CheckpointSaveFn save, CheckpointRestoreFn restore);

  /// `bhnsid run FILE --warm-start DIR`: after INITIAL, `fn` reads this plugin's section of the
  /// newest checkpoint of another run DIR of the same build whose parameters differ only in
  /// steerable ones (the previous run of a parameter scan), or by one refinement of every parameter
  /// declared with refines() (the next coarser run of a convergence series: the fields of the
  /// checkpoint are then on a lattice of twice the spacing, and `fn` interpolates them or keeps
  /// INITIAL's; a plugin that reads them as they are gets InputError for the sizes, a clear refusal).
  /// It takes what is a good start for these parameters and leaves what they decide (and any
  /// convergence history) as INITIAL made it. The loop then starts at iteration 1.
  void warm_start(CheckpointRestoreFn fn);

 private:
  ParamHandle add_param(std::string name, ParamType type);
  PluginDecl& decl_;
};

/// Checks what a plugin declared (names, docs, defaults inside ranges, unique entries); throws
/// InputError naming the plugin, since a malformed declaration is the plugin author's input error.
void validate_declaration(const PluginDecl& decl);

}  // namespace bhnsid::core

extern "C" {
struct BhnsidPluginInfo {
  std::uint32_t abi_version;
  const char* name;
  const char* version;
  const char* description;
  void (*declare)(bhnsid::core::PluginBuilder&);
};
}
