// Test plugin: one parameter of every type, an entry in every bin, a CHECK that converges after
// `converge_after` iterations, a service, and a switch to fail in a chosen bin. It records the
// order in which its entries ran into order.txt (OUTPUT) and terminate.txt (TERMINATE).
#include <chrono>
#include <memory>
#include <thread>
#include <string>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/errors.hpp"
#include "bhnsid/core/plugin.hpp"
#include "tp_interfaces.hpp"

namespace {
using namespace bhnsid::core;

struct State {
  std::string order;
  std::shared_ptr<bhnsid::test::CounterService> counter = std::make_shared<bhnsid::test::CounterService>();
};

void maybe_fail(Context& ctx, const char* where) {
  if (ctx.params().string("fail_in") == where) throw RunFailure(std::string("deliberate failure in ") + where);
}

void declare(PluginBuilder& b) {
  auto s = std::make_shared<State>();
  b.implements("counter");
  b.boolean("flag").doc("a bool").default_value(false);
  b.integer("count").doc("an int in [0, 1000]").default_value(std::int64_t{5}).at_least(0).at_most(1000);
  b.real("scale").doc("a real in (0, 10]").default_value(1.0).greater_than(0).at_most(10);
  b.string("label").doc("a string").default_value(std::string("hello"));
  b.keyword("mode", {"alpha", "beta", "gamma"}).doc("a keyword").default_value(std::string("alpha"));
  b.real_vector("vec").doc("three reals").default_value(std::vector<double>{0, 0, 0}).length(3);
  b.real("needed").doc("a required real (units of nothing)").required(1.5);
  b.integer("converge_after").doc("iterations until CHECK converges; 0 never").default_value(std::int64_t{3}).at_least(0);
  b.keyword("fail_in", {"none", "setup", "solve", "output"}).doc("bin to fail in").default_value(std::string("none"));
  b.integer("sleep_ms").doc("milliseconds each SOLVE takes (concurrent runs, signals)").default_value(std::int64_t{0}).at_least(0).at_most(60000);
  b.variable({"tp_scalar", TensorKind::scalar, TimeParity::even, Storage::all_levels, "a scalar field", ""});

  const auto record = [s](const char* tag) { return [s, tag](Context&) { s->order += std::string(tag) + "\n"; }; };
  b.schedule(Bin::startup, "startup", [s](Context& ctx) {
    s->order += "startup\n";
    ctx.publish("counter", s->counter);
  });
  b.schedule(Bin::paramcheck, "paramcheck", record("paramcheck"));
  b.schedule(Bin::setup, "setup", [s](Context& ctx) {
    s->order += "setup\n";
    maybe_fail(ctx, "setup");
  });
  b.schedule(Bin::initial, "initial", record("initial")).doc("initial data");
  b.schedule(Bin::solve, "solve", [s](Context& ctx) {
    s->order += "solve\n";
    std::this_thread::sleep_for(std::chrono::milliseconds(ctx.params().integer("sleep_ms")));
    s->counter->value += 1;
    maybe_fail(ctx, "solve");
  });
  b.schedule(Bin::update, "update", record("update"));
  b.check("check", [s](Context& ctx) {
    s->order += "check\n";
    ctx.set_scalar("counter", s->counter->value);
    const auto after = ctx.params().integer("converge_after");
    return Convergence{after > 0 && ctx.iteration() >= after, "counter " + std::to_string(s->counter->value)};
  });
  b.schedule(Bin::analysis, "analysis", [s](Context& ctx) {
    s->order += "analysis\n";
    ctx.set_scalar("scale_times_count", ctx.params().real("scale") * static_cast<double>(ctx.params().integer("count")));
  });
  b.schedule(Bin::output, "output", [s](Context& ctx) {
    s->order += "output\n";
    maybe_fail(ctx, "output");
    ctx.write_output("order.txt", s->order);
  });
  b.schedule(Bin::terminate, "terminate", [s](Context& ctx) { ctx.write_output("terminate.txt", s->order + "terminate\n"); });
}
}  // namespace

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "tp_counter", "1.0", "test: every parameter type and bin", &declare};
  return &info;
}
