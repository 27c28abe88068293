# The test reads data.h5 with the HDF5 C API alone, as an importer would.
find_package(HDF5 REQUIRED COMPONENTS C)
set(uses_include ${HDF5_INCLUDE_DIRS})
set(uses_libraries ${HDF5_C_LIBRARIES})
