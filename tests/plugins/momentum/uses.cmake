# The curvature-fill tests run on the real serial grid (several levels, ghosts by parity).
set(uses_plugin grid)
set(uses_sources uniform_grid.cpp blocks.cpp grid_sampling.cpp hierarchy.cpp)
