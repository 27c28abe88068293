#pragma once
// Typed errors that the CLI maps to exit codes: bad input of any kind (parameter file, plugin files,
// output directory) is an InputError (exit 2); a physics run that cannot reach its answer is a
// RunFailure (status "failed", exit 1, OUTPUT and TERMINATE still run).
#include <stdexcept>
#include <string>

namespace bhnsid::core {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what);
  ~InputError() override;
};

class RunFailure : public std::runtime_error {
 public:
  explicit RunFailure(const std::string& what);
  ~RunFailure() override;
};

/// A SOLVE entry's failure that a smaller outer step may cure (a solve that diverged, produced
/// non-finite values or stalled after the sources moved): inside the loop, when RETREAT entries
/// exist and run.max_retreats allows, the core runs RETREAT, then UPDATE again with half the step
/// (Context::step_fraction), then SOLVE; elsewhere it is an ordinary RunFailure.
class StepFailure : public RunFailure {
 public:
  explicit StepFailure(const std::string& what);
  ~StepFailure() override;
};

/// A stopping signal ended a command early (exit 128 + the signal, see interrupt.hpp).
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(const std::string& what);
  ~Interrupted() override;
};

/// Process exit codes, stable for scripts and tests.
/// An interrupted run exits 128 + the signal: 130 (SIGINT), 143 (SIGTERM), 129 (SIGHUP).
enum ExitCode : int { exit_ok = 0, exit_run_failed = 1, exit_input = 2, exit_internal = 3 };

}  // namespace bhnsid::core
