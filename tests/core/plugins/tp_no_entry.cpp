// Test plugin: a shared library without the entry point.
#include "bhnsid/core/plugin.hpp"

extern "C" BHNSID_EXPORT int bhnsid_something_else() { return 42; }
