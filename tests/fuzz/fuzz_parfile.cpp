// libFuzzer target for the whole path a user's input takes before a run starts: file bytes ->
// parse_yaml -> parse_parfile -> --set override -> configure (the real plugins of this build,
// loaded from its plugin folder) -> check_parameters (every PARAMCHECK entry, the thread bound and
// the memory estimate), i.e. exactly what `bhnsid check` does; and, beside it, resolve_params
// against a fixture with one parameter of every type. A parameter file is the one input a user (or
// a script writing one) fully controls, so any input must end either in a result or in an
// InputError that the CLI turns into exit 2. Anything else (another exception, a crash, a sanitizer report, a
// stack overflow, a hang) is a bug, and is deliberately left to escape so libFuzzer records it.
// The same file is built without libFuzzer into replay_fuzz_parfile (see replay_main.cpp).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "bhnsid/core/configuration.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/parfile.hpp"
#include "bhnsid/core/run.hpp"

using namespace bhnsid::core;

namespace {

// One parameter of every type and check, so that every branch of convert_value/check_value is
// reachable from the input; "inactive_plugin" is passed as a known but inactive plugin so that
// the "section of an inactive plugin" error is reachable too.
const PluginDecl& fuzzed_declaration() {
  static const PluginDecl decl = [] {
    PluginDecl d;
    d.name = "fuzzed";
    d.version = "fuzz";
    d.description = "every parameter type, for the fuzz target";
    PluginBuilder b(d);
    b.boolean("flag").doc("a bool").default_value(false);
    b.integer("count").doc("an int in [1, 1000]").default_value(std::int64_t{10}).at_least(1).at_most(1000);
    b.real("spacing").doc("a real in (0, 1)").default_value(0.5).greater_than(0).less_than(1);
    b.string("label").doc("any string").default_value(std::string("x"));
    b.keyword("mode", {"none", "equatorial", "full"}).doc("a keyword").default_value(std::string("none"));
    b.real_vector("spin").doc("3 reals").default_value(std::vector<double>{0, 0, 0}).length(3);
    b.real("mass").doc("required").required(1.0).greater_than(0);
    validate_declaration(d);  // a broken fixture would make every run an InputError: fail loudly
    return d;
  }();
  return decl;
}

const std::vector<const PluginDecl*>& active() {
  static const std::vector<const PluginDecl*> decls{&core_declaration(), &fuzzed_declaration()};
  return decls;
}

// A value that resolve_params hands to plugins must already satisfy its declaration: plugins read
// it without checking again. Checked here so the fuzzer also finds silent acceptance bugs.
void check_resolved(const std::map<std::string, ParamSection>& resolved) {
  for (const auto* decl : active()) {
    const auto section = resolved.find(decl->name);
    if (section == resolved.end()) {
      std::fprintf(stderr, "fuzz_parfile: resolve_params returned without section '%s'\n", decl->name.c_str());
      std::abort();
    }
    for (const auto& spec : decl->params) {
      const auto value = section->second.values().find(spec.name);
      if (value == section->second.values().end() || !check_value(spec, value->second).empty()) {
        std::fprintf(stderr, "fuzz_parfile: %s.%s missing or out of its declared range\n", decl->name.c_str(),
                     spec.name.c_str());
        std::abort();
      }
    }
  }
}

// The real plugins, as `bhnsid check` finds them next to the executable; loaded once (dlopen is
// the expensive part and loading is side-effect free).
PluginLoader& real_plugins() {
  static PluginLoader loader(plugin_search_path({}));
  static const bool loaded = [] {
    if (loader.available().empty()) {
      std::fprintf(stderr, "fuzz_parfile: no plugins on the plugin path; build them first\n");
      std::abort();
    }
    for (const auto& [name, file] : loader.available()) loader.load(name);
    return true;
  }();
  (void)loaded;
  return loader;
}

// `bhnsid check` on the input; comment lines "#set section.key=value" (which YAML ignores) become
// --set overrides, as on the command line.
void check_like_the_cli(const std::string& text) {
  std::vector<std::string> overrides;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    if (text.compare(start, 4, "#set") == 0) overrides.push_back(text.substr(start + 4, end - start - 4));
    start = end + 1;
  }
  try {
    const Configuration config = configure(parse_parfile(parse_yaml(text, "fuzz.yaml")), overrides, real_plugins());
    const MemoryEstimate estimate = check_parameters(config);
    if (!(estimate.total() > 0)) {
      std::fprintf(stderr, "fuzz_parfile: a memory estimate of %g bytes\n", estimate.total());
      std::abort();
    }
  } catch (const InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  check_like_the_cli(text);
  try {
    check_resolved(resolve_params(parse_parfile(parse_yaml(text, "fuzz.yaml")), active(), {"inactive_plugin"}));
  } catch (const InputError&) {
  }

  // The override goes onto a fixed valid file rather than the input's own, which is usually
  // invalid: that way the overridden value itself gets resolved and range-checked.
  const std::string line = text.substr(0, text.find('\n'));
  if (line.find('=') != std::string::npos) {
    static const ParFile base = parse_parfile(parse_yaml("plugins: [fuzzed]\nfuzzed:\n  mass: 1.0\n", "base.yaml"));
    try {
      ParFile file = base;
      apply_override(file, line);
      check_resolved(resolve_params(file, active(), {"inactive_plugin"}));
    } catch (const InputError&) {
    }
  }
  return 0;
}
