#pragma once
// The state one run shares between the core and every plugin's Context.
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "bhnsid/core/configuration.hpp"
#include "bhnsid/core/run_directory.hpp"
#include "bhnsid/core/services.hpp"
#include "log_sink.hpp"

namespace bhnsid::core {

struct RunState {
  explicit RunState(const Configuration& c) : config(c) {}
  const Configuration& config;
  LogSink sink;
  Services services;
  std::filesystem::path run_dir;
  RunDirectory* directory = nullptr;  ///< records what the run writes; null for check and schedule
  int iteration = 0;
  double step_fraction = 1;  ///< see Context::step_fraction
  bool in_loop = false;
  std::vector<std::pair<std::string, double>> scalars;  ///< summary.json order: first set, first listed
  std::vector<std::string> history_columns;
  std::vector<std::map<std::string, double>> history;  ///< one row per loop iteration
  std::vector<std::pair<std::string, double>> progress;  ///< show_progress() of this iteration
  std::string resolved_parameters;                        ///< params.yaml as written
  std::vector<std::pair<std::string, std::string>> provenance;
  std::string failure;  ///< the first failure, once there is one
  bool initial_data = false;  ///< STARTUP to INITIAL completed
};

}  // namespace bhnsid::core
