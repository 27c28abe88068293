# The SLy frozen-profile and upper-branch tests build the piecewise polytrope itself.
set(uses_plugin eos_piecewise_polytrope)
set(uses_sources piecewise_polytrope.cpp)
