// The flow_corotating plugin (implements "flow"): the star's fluid at rest in the frame rotating with
// the orbit (corotation, the paper's ansatz). The star plugin reads it through the Flow interface.
#include <memory>

#include "bhnsid/core/context.hpp"
#include "bhnsid/core/plugin.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "corotation.hpp"

namespace bhnsid::flow_corotating {
namespace {

using core::Bin;
using core::Context;

void declare(core::PluginBuilder& b) {
  auto flow = std::make_shared<Corotation>();
  b.require("lapse");
  b.require("star");
  b.implements("flow");
  b.schedule(Bin::startup, "publish", [flow](Context& ctx) { ctx.publish<Flow>("flow", flow); })
      .doc("publish the corotating flow for the star");
  b.schedule(Bin::setup, "setup", [flow](Context& ctx) { flow->attach(ctx.services().get<Lapse>("lapse")); })
      .after("lapse.setup")
      .doc("read alpha from the lapse");
}

}  // namespace
}  // namespace bhnsid::flow_corotating

extern "C" BHNSID_EXPORT const BhnsidPluginInfo* bhnsid_plugin_info() {
  static const BhnsidPluginInfo info{BHNSID_ABI_VERSION, "flow_corotating", "0.1",
                                     "corotating flow: v = (beta + Omega xi)/alpha, first integral h/u^t = C_B",
                                     &bhnsid::flow_corotating::declare};
  return &info;
}
