# The potential solver is tested on the real serial grid.
set(uses_plugin grid)
set(uses_sources uniform_grid.cpp blocks.cpp grid_sampling.cpp hierarchy.cpp)
