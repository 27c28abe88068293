# The diagnostics are tested on the real serial grid (its integrals, faces and symmetry).
set(uses_plugin grid)
set(uses_sources uniform_grid.cpp blocks.cpp grid_sampling.cpp hierarchy.cpp)
