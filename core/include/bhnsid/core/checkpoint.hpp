#pragma once
// Checkpoints: after every loop iteration the core asks each plugin that declared a checkpoint
// (PluginBuilder::checkpoint) to save its state, and `bhnsid run FILE --resume` hands it back after
// INITIAL, so that the loop continues as if it had never stopped. A plugin saves what its next
// SOLVE, UPDATE, CHECK, ANALYSIS and OUTPUT read and INITIAL does not recreate: fields, constants,
// the history its convergence test compares with, warm solver state. Entries are named; the core
// adds the plugin's name, so names need only be unique within a plugin.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace bhnsid::core {

class Context;

class CheckpointWriter {
 public:
  virtual ~CheckpointWriter() = default;
  void put(const std::string& name, const double* values, std::size_t count) { record(name, 'd', values, count * sizeof(double)); }
  void put(const std::string& name, const std::vector<double>& values) { put(name, values.data(), values.size()); }
  void put(const std::string& name, double value) { put(name, &value, 1); }
  void put_integer(const std::string& name, std::int64_t value) { record(name, 'i', &value, sizeof value); }
  void put_integers(const std::string& name, const std::vector<std::int64_t>& values) {
    record(name, 'i', values.data(), values.size() * sizeof(std::int64_t));
  }
  void put_string(const std::string& name, const std::string& value) { record(name, 's', value.data(), value.size()); }
  void put_bytes(const std::string& name, const void* data, std::size_t bytes) { record(name, 'b', data, bytes); }

 protected:
  /// type: 'd' doubles, 'i' 64-bit integers, 's' a string, 'b' raw bytes.
  virtual void record(const std::string& name, char type, const void* data, std::size_t bytes) = 0;
};

/// Every accessor throws InputError naming the checkpoint file, the plugin and the entry when the
/// entry is missing or of another type or size: a checkpoint of another build or run is refused,
/// never half restored.
class CheckpointReader {
 public:
  virtual ~CheckpointReader() = default;
  virtual bool has(const std::string& name) const = 0;
  void get(const std::string& name, double* out, std::size_t count) const { read(name, 'd', out, count * sizeof(double)); }
  std::vector<double> reals(const std::string& name) const;
  double real(const std::string& name) const {
    double v = 0;
    get(name, &v, 1);
    return v;
  }
  std::int64_t integer(const std::string& name) const {
    std::int64_t v = 0;
    read(name, 'i', &v, sizeof v);
    return v;
  }
  std::vector<std::int64_t> integers(const std::string& name) const;
  std::string string(const std::string& name) const;
  void get_bytes(const std::string& name, void* out, std::size_t bytes) const { read(name, 'b', out, bytes); }

 protected:
  /// The size in bytes of entry `name` of `type`; throws as described above when absent.
  virtual std::size_t size(const std::string& name, char type) const = 0;
  /// Reads exactly `bytes` of entry `name`; throws when its type or size differs.
  virtual void read(const std::string& name, char type, void* out, std::size_t bytes) const = 0;
};

using CheckpointSaveFn = std::function<void(Context&, CheckpointWriter&)>;
using CheckpointRestoreFn = std::function<void(Context&, const CheckpointReader&)>;

}  // namespace bhnsid::core
