#include "run_checkpoint.hpp"

#include <dlfcn.h>
#include <sys/stat.h>
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "bhnsid/core/build_info.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/owned_entry.hpp"

namespace bhnsid::core {

namespace fs = std::filesystem;

namespace {

std::uint64_t hash_file(std::uint64_t hash, const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read it to identify the build: {}", file.string(), "unreadable"));
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    hash = fnv1a(hash, buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  return hash;
}

// Parameters that only steer how far the loop goes and how often it is saved: a resume may change
// them (give a run that ran out of iterations more), nothing else.
bool may_differ(const std::string& key) {
  // run.threads changes the result only at round-off (the warning below says so, and how to avoid it).
  return key == "run.max_iterations" || key == "run.threads" || key == "run.checkpoint_every" || key == "run.checkpoint_overhead";
}

std::map<std::string, std::string> fingerprint_lines(const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const std::size_t eq = line.find(" = ");
    if (eq != std::string::npos) out[line.substr(0, eq)] = line.substr(eq + 3);
  }
  return out;
}

std::string join(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) out += w + "\n";
  return out;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

int threads_now() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// Every parameter of `config` equals the one the checkpoint `f` was written with, except those
// `may_change` lets through; InputError naming the parameter file, the key and both values.
void check_parameters_match(CheckpointFileReader& f, const Configuration& config,
                            const std::function<bool(const std::string&)>& may_change, const std::string& advice) {
  f.section(core_section);
  const auto was = fingerprint_lines(f.string("parameters"));
  const auto now = fingerprint_lines(parameter_fingerprint(config));
  // Another plugin set first, by the plugins that differ: its parameters would differ as a consequence.
  const auto words = [](const std::map<std::string, std::string>& lines) {
    std::set<std::string> out;
    const auto it = lines.find("plugins");
    std::istringstream in(it == lines.end() ? std::string() : it->second);
    for (std::string w; in >> w;) out.insert(w);
    return out;
  };
  const std::set<std::string> plugins_was = words(was), plugins_now = words(now);
  if (plugins_was != plugins_now) {
    std::vector<std::string> added, missing;
    for (const auto& p : plugins_now)
      if (!plugins_was.count(p)) added.push_back(p);
    for (const auto& p : plugins_was)
      if (!plugins_now.count(p)) missing.push_back(p);
    throw InputError(fmt::format("{}: plugins: the checkpoint {} was written by another plugin set ({}{}{}); {}",
                                 config.file.source, f.path().string(),
                                 added.empty() ? "" : fmt::format("this run adds {}", fmt::join(added, ", ")),
                                 !added.empty() && !missing.empty() ? ", " : "",
                                 missing.empty() ? "" : fmt::format("this run lacks {}", fmt::join(missing, ", ")), advice));
  }
  for (const auto& [key, value] : now) {
    if (key == "plugins") continue;  // the order of the list is the schedule's business, not the state's
    if (may_change(key)) continue;
    auto it = was.find(key);
    if (it == was.end() || it->second != value)
      throw InputError(fmt::format("{}: {}: the checkpoint {} was written with {}, this run has {} = {}; {}",
                                   config.file.source, key, f.path().string(),
                                   it == was.end() ? "no such parameter" : key + " = " + it->second, key, value, advice));
  }
  for (const auto& [key, value] : was)
    if (!may_change(key) && !now.count(key))
      throw InputError(fmt::format("{}: the checkpoint {} was written with {} = {}, which this run does not have (another "
                                   "plugin set); {}",
                                   config.file.source, f.path().string(), key, value, advice));
}

// The declaration of `key` ("section.name") by its plugin; null when no plugin declares it.
const ParamSpec* find_spec(const Configuration& config, const std::string& key) {
  const std::size_t dot = key.find('.');
  if (dot == std::string::npos) return nullptr;
  for (const auto* decl : config.decls)
    if (decl->name == key.substr(0, dot)) return decl->find_param(key.substr(dot + 1));
  return nullptr;
}

// A parameter its plugin declared steerable: one that may differ between the runs of a sequence.
bool steerable(const Configuration& config, const std::string& key) {
  const ParamSpec* spec = find_spec(config, key);
  return spec && spec->steerable;
}

// How the plugin of `key` declared it to follow the spacing (bhnsid validate); none for others.
Refinement refinement(const Configuration& config, const std::string& key) {
  const ParamSpec* spec = find_spec(config, key);
  return spec ? spec->refinement : Refinement::none;
}

// `now` is `was` after one halving of the spacing: twice it (a point count) or half it (a spacing).
bool one_refinement(Refinement how, const std::string& was, const std::string& now) {
  char* end = nullptr;
  const double a = std::strtod(was.c_str(), &end);
  if (end == was.c_str() || *end != '\0') return false;
  const double b = std::strtod(now.c_str(), &end);
  if (end == now.c_str() || *end != '\0') return false;
  const double expected = how == Refinement::doubles ? 2 * a : 0.5 * a;
  return std::fabs(b - expected) <= 1e-12 * std::fabs(expected);
}

// The parameters that follow the spacing, of a warm start from the next coarser run of a
// convergence series (grid.n doubled, grid.dx halved, ...): all of them exactly one refinement
// away, or none of them changed. Returns the refined keys (empty: the same lattice); InputError
// when only some are refined or one by another factor, naming them.
std::vector<std::string> refined_keys(const std::map<std::string, std::string>& was, const std::string& fingerprint,
                                      const Configuration& config, const std::string& file) {
  std::vector<std::string> refined, same;
  for (const auto& [key, value] : fingerprint_lines(fingerprint)) {
    const Refinement how = refinement(config, key);
    auto it = was.find(key);
    if (how == Refinement::none || it == was.end()) continue;
    if (it->second == value)
      same.push_back(key);
    else if (one_refinement(how, it->second, value))
      refined.push_back(key);
    else
      throw InputError(fmt::format("{}: {}: the checkpoint {} was written with {} = {}, this run has {}; a warm start "
                                   "reads a run of the same lattice or of the next coarser one ({} {} here)",
                                   config.file.source, key, file, key, it->second, value, key,
                                   how == Refinement::doubles ? "half" : "twice"));
  }
  if (!refined.empty() && !same.empty())
    throw InputError(fmt::format("{}: the checkpoint {} is refined in {} but not in {}; a warm start from the next "
                                 "coarser run needs every parameter that follows the spacing refined once",
                                 config.file.source, file, refined.front(), same.front()));
  return refined;
}

// The parts of the build that differ between a checkpoint and this run ("plugin lapse, core library");
// empty when the checkpoint does not say (then the ids alone tell).
std::string build_difference(CheckpointFileReader& f, const std::string& ours) {
  if (!f.has("build_files")) return {};
  const auto lines = [](const std::string& text) {
    std::map<std::string, std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      const std::size_t tab = line.find('\t');
      if (tab != std::string::npos) out[line.substr(0, tab)] = line.substr(tab + 1);
    }
    return out;
  };
  const auto theirs = lines(f.string("build_files")), now = lines(ours);
  std::vector<std::string> changed;
  for (const auto& [part, value] : now) {
    auto it = theirs.find(part);
    if (it != theirs.end() && it->second != value)
      changed.push_back(part == "version" ? fmt::format("version ({} -> {})", it->second, value) : part);
  }
  return changed.empty() ? std::string() : fmt::format("; changed: {}", fmt::join(changed, ", "));
}

// Same build as the checkpoint's, or InputError naming what changed.
void check_build(CheckpointFileReader& f, const std::string& build, const std::string& who, const std::string& advice) {
  f.section(core_section);
  const std::string theirs = f.string("build_id"), ours = build_id_of(build);
  if (theirs != ours)
    throw InputError(fmt::format("{}{}: written by another build of bhnsid (build id {}, this one {}{}); {}", who,
                                 f.path().string(), theirs, ours, build_difference(f, build), advice));
}

}  // namespace

std::string build_description(const Configuration& config) {
  std::string out = fmt::format("version\t{} {} {} {}\n", build_version(), build_git_revision(), build_type(), build_compiler());
  const auto file_line = [&out](const std::string& role, const fs::path& file) {
    out += fmt::format("{}\t{:016x}\n", role, hash_file(fnv_offset, file));
  };
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) file_line("executable", exe);
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&fnv1a), &info) != 0 && info.dli_fname) file_line("core library", info.dli_fname);
  for (const auto& plugin : config.plugins) file_line("plugin " + plugin->decl.name, plugin->file);
  return out;
}

std::string build_id_of(const std::string& description) {
  return fmt::format("{:016x}", fnv1a(fnv_offset, description.data(), description.size()));
}

std::string parameter_fingerprint(const Configuration& config) {
  std::string out = "plugins = ";
  for (const auto& p : config.plugins) out += p->decl.name + " ";
  out += "\n";
  for (const auto& [section, values] : config.params)
    for (const auto& [key, value] : values.values()) out += fmt::format("{}.{} = {}\n", section, key, format_value(value));
  return out;
}

void save_checkpoint(RunState& state, const ContextOf& context, bool converged, const std::string& build) {
  const fs::path dir = state.run_dir / checkpoint_dir_name;
  state.directory->record_folder(checkpoint_dir_name);
  std::error_code ec;
  // A symbolic link there would have the rotation below delete another folder's files.
  if (!require_own_entry(dir, EntryKind::folder) && ::mkdir(dir.c_str(), 0755) != 0 && errno != EEXIST)
    throw InputError(fmt::format("{}: cannot create the checkpoint folder: {}", dir.string(), std::strerror(errno)));
  const fs::path final_path = checkpoint_path(dir, state.iteration);
  fs::path partial = final_path;
  partial += ".partial";
  {
    CheckpointFileWriter w(partial);
    w.section(core_section);
    w.put_string("build_id", build_id_of(build));
    w.put_string("build_files", build);
    w.put_string("parameters", parameter_fingerprint(state.config));
    w.put_integer("iteration", state.iteration);
    w.put_integer("converged", converged ? 1 : 0);
    w.put_integer("threads", threads_now());
    w.put_string("history_columns", join(state.history_columns));
    // One row per iteration in column order; a cell a plugin did not set that iteration is marked
    // absent in the mask (it is written empty in scalars.tsv, which NaN would not be).
    std::vector<double> cells;
    std::string present;
    for (const auto& row : state.history)
      for (const auto& c : state.history_columns) {
        auto it = row.find(c);
        cells.push_back(it == row.end() ? 0.0 : it->second);
        present.push_back(it == row.end() ? '0' : '1');
      }
    w.put("history", cells);
    w.put_string("history_present", present);
    std::vector<std::string> names;
    std::vector<double> values;
    for (const auto& [name, value] : state.scalars) {
      names.push_back(name);
      values.push_back(value);
    }
    w.put_string("scalar_names", join(names));
    w.put("scalar_values", values);
    for (const auto* decl : state.config.decls)
      if (decl->checkpoint_save) {
        w.section(decl->name);
        decl->checkpoint_save(context(decl->name), w);
      }
    w.finish(final_path);
  }
  const std::vector<int> kept = checkpoint_iterations(dir);
  for (std::size_t i = 2; i < kept.size(); ++i) fs::remove(checkpoint_path(dir, kept[i]), ec);
}

ResumePoint find_resume_point(const fs::path& run_dir, const Configuration& config, const std::string& build,
                              const Log& log) {
  const fs::path dir = run_dir / checkpoint_dir_name;
  require_own_entry(dir, EntryKind::folder);
  std::error_code ec;
  // A write a kill interrupted: never a checkpoint, and ours to remove.
  for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("checkpoint.", 0) == 0 && name.size() > 8 && name.compare(name.size() - 8, 8, ".partial") == 0) {
      if (!require_own_entry(it->path(), EntryKind::regular_file)) continue;
      log.warn("{}: an unfinished checkpoint write (the run was killed while saving); removed", it->path().string());
      fs::remove(it->path(), ec);
    }
  }
  const std::vector<int> iterations = checkpoint_iterations(dir);
  if (iterations.empty())
    throw InputError(fmt::format("{}: no checkpoint to resume from (the run stopped before its first loop iteration "
                                 "ended, or run.checkpoint_every = 0); start it again with --force",
                                 dir.string()));
  std::string refused;
  for (int iteration : iterations) {
    ResumePoint point;
    try {
      point.file = std::make_unique<CheckpointFileReader>(checkpoint_path(dir, iteration));
    } catch (const InputError& e) {
      log.warn("{}; trying an older checkpoint", e.what());
      refused += fmt::format("{} {}", refused.empty() ? "" : ";", e.what());
      continue;
    }
    CheckpointFileReader& f = *point.file;
    // The plugin set and the parameters first: another parameter file is named as such, not taken
    // for another build (the build id covers the plugins loaded).
    check_parameters_match(f, config, may_differ,
                           "resume with the parameters of the run (only run.max_iterations, run.threads and the "
                           "checkpoint settings may change) or start again with --force");
    check_build(f, build, "", "resume with the build that wrote it, or start again with --force");
    f.section(core_section);
    const std::int64_t threads = f.integer("threads");
    if (threads != threads_now())
      log.warn("{}: written with {} OpenMP threads, this run has {}: the result will agree to round-off, not to the bit "
               "(reductions sum in another order); set run.threads = {} for an identical result",
               f.path().string(), threads, threads_now(), threads);
    point.iteration = static_cast<int>(f.integer("iteration"));
    point.converged = f.integer("converged") != 0;
    return point;
  }
  throw InputError(fmt::format("{}: no checkpoint there reads back whole:{}; start the run again with --force",
                               dir.string(), refused));
}

WarmPoint find_warm_point(const fs::path& source_dir, const Configuration& config, const std::string& build) {
  const fs::path dir = source_dir / checkpoint_dir_name;
  require_own_entry(dir, EntryKind::folder);
  const std::vector<int> iterations = checkpoint_iterations(dir);
  if (iterations.empty())
    throw InputError(fmt::format("--warm-start {}: no checkpoint there (not a run directory, the run stopped before its "
                                 "first loop iteration ended, or run.checkpoint_every = 0)",
                                 source_dir.string()));
  WarmPoint point;
  // The newest only: a warm start from an older state than the neighbour's last is not what was asked.
  point.file = std::make_unique<CheckpointFileReader>(checkpoint_path(dir, iterations.front()));
  CheckpointFileReader& f = *point.file;
  f.section(core_section);
  const auto was = fingerprint_lines(f.string("parameters"));
  const std::vector<std::string> refined = refined_keys(was, parameter_fingerprint(config), config, f.path().string());
  point.refined = !refined.empty();
  const auto may_change = [&config, &refined](const std::string& key) {
    return may_differ(key) || steerable(config, key) || std::find(refined.begin(), refined.end(), key) != refined.end();
  };
  check_parameters_match(f, config, may_change,
                         "a warm start may change only steerable parameters (bhnsid params marks them [steerable]) and "
                         "refine the lattice by one step");
  check_build(f, build, "--warm-start ",
              "a warm start reads the plugins' own state, which only the same build knows");
  f.section(core_section);
  for (const auto& [key, value] : fingerprint_lines(parameter_fingerprint(config))) {
    auto it = was.find(key);
    if (it != was.end() && it->second != value && !may_differ(key))
      point.changed += fmt::format("{}{} {} -> {}", point.changed.empty() ? "" : ", ", key, it->second, value);
  }
  point.iteration = static_cast<int>(f.integer("iteration"));
  point.converged = f.integer("converged") != 0;
  return point;
}

void apply_warm_start(RunState& state, const ContextOf& context, CheckpointFileReader& f) {
  for (const auto* decl : state.config.decls) {
    if (!decl->warm_start || !f.has_section(decl->name)) continue;
    f.section(decl->name);
    decl->warm_start(context(decl->name), f);
  }
}

void restore_checkpoint(RunState& state, const ContextOf& context, CheckpointFileReader& f) {
  f.section(core_section);
  state.iteration = static_cast<int>(f.integer("iteration"));
  state.history_columns = split(f.string("history_columns"));
  const std::vector<double> cells = f.reals("history");
  const std::string present = f.string("history_present");
  const std::size_t columns = state.history_columns.size();
  if (present.size() != cells.size() || (columns == 0 ? !cells.empty() : cells.size() % columns != 0))
    throw InputError(fmt::format("{}: the loop history is malformed", f.path().string()));
  state.history.clear();
  for (std::size_t r = 0; columns > 0 && r < cells.size() / columns; ++r) {
    auto& row = state.history.emplace_back();
    for (std::size_t c = 0; c < columns; ++c)
      if (present[r * columns + c] == '1') row[state.history_columns[c]] = cells[r * columns + c];
  }
  const std::vector<std::string> names = split(f.string("scalar_names"));
  const std::vector<double> values = f.reals("scalar_values");
  if (names.size() != values.size()) throw InputError(fmt::format("{}: the scalars are malformed", f.path().string()));
  state.scalars.clear();
  for (std::size_t i = 0; i < names.size(); ++i) state.scalars.emplace_back(names[i], values[i]);
  for (const auto* decl : state.config.decls) {
    const bool saved = f.has_section(decl->name);
    if (saved != static_cast<bool>(decl->checkpoint_restore))
      throw InputError(fmt::format("{}: plugin {} {} a checkpoint section, but {}", f.path().string(), decl->name,
                                   saved ? "has" : "has no", saved ? "restores none" : "needs one"));
    if (!saved) continue;
    f.section(decl->name);
    decl->checkpoint_restore(context(decl->name), f);
  }
}

}  // namespace bhnsid::core
