#pragma once
// A test-only service interface shared by the test plugins (real interfaces live in core/).
#include "bhnsid/core/services.hpp"

namespace bhnsid::test {
struct CounterService : core::Service {
  int value = 0;
};
}  // namespace bhnsid::test
