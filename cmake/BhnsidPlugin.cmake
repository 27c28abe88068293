# bhnsid_add_plugin(NAME SOURCES a.cpp b.cpp ... [TEST_ONLY] [PLOT script.py])
# Builds libbhnsid_NAME.so into the plugin folder (build/lib/bhnsid), or, for TEST_ONLY plugins
# used by the core's tests, into build/test-plugins where a normal run never finds them.
# Only the entry point is exported; everything else stays private to the plugin.
# Unit tests of a plugin link bhnsid_NAME_objects (its code, headers on the include path).
define_property(GLOBAL PROPERTY BHNSID_PLUGIN_TARGETS BRIEF_DOCS "plugin targets" FULL_DOCS "all plugin targets")

function(bhnsid_add_plugin name)
  cmake_parse_arguments(ARG "TEST_ONLY" "PLOT" "SOURCES" ${ARGN})
  set(target bhnsid_${name})
  # The objects are a target of their own so that the plugin's unit tests (tests/plugins/NAME)
  # can link the same code the shared library is made of.
  add_library(${target}_objects OBJECT ${ARG_SOURCES})
  target_link_libraries(${target}_objects PUBLIC bhnsid_core)
  target_include_directories(${target}_objects PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  set_target_properties(${target}_objects PROPERTIES
    POSITION_INDEPENDENT_CODE ON CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
  add_library(${target} MODULE $<TARGET_OBJECTS:${target}_objects>)
  target_link_libraries(${target} PRIVATE bhnsid_core)
  if(ARG_TEST_ONLY)
    set(out ${BHNSID_TEST_PLUGIN_DIR})
  else()
    set(out ${BHNSID_PLUGIN_OUTPUT_DIR})
  endif()
  set_target_properties(${target} PROPERTIES
    PREFIX "lib"
    LIBRARY_OUTPUT_DIRECTORY ${out}
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    BUILD_RPATH "$ORIGIN/.."
    INSTALL_RPATH "$ORIGIN/..")
  # PLOT script.py: copied beside the library as NAME.plot.py, which `bhnsid plot RUN_DIR` runs.
  if(ARG_PLOT)
    configure_file(${CMAKE_CURRENT_SOURCE_DIR}/${ARG_PLOT} ${out}/${name}.plot.py COPYONLY)
  endif()
  # make install: beside the others in <prefix>/lib/bhnsid, where bin/bhnsid looks (../lib/bhnsid);
  # INSTALL_RPATH $ORIGIN/.. finds libbhnsid_core in <prefix>/lib. Test-only plugins stay behind.
  if(NOT ARG_TEST_ONLY)
    install(TARGETS ${target} LIBRARY DESTINATION lib/bhnsid COMPONENT solver)
    if(ARG_PLOT)
      install(FILES ${out}/${name}.plot.py DESTINATION lib/bhnsid COMPONENT solver)
    endif()
  endif()
  set_property(GLOBAL APPEND PROPERTY BHNSID_PLUGIN_TARGETS ${target})
endfunction()
