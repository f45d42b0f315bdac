# cmake --install into a temporary prefix, then the installed package imported and run by plain
# python3 from there, and the plugin file present where ParaView's PV_PLUGIN_PATH would point.
# Variables: BUILD_DIR, PREFIX, PYTHON, PYTHON_DESTINATION, PLUGIN_SUBDIR.
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}"
  RESULT_VARIABLE result OUTPUT_QUIET)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${result}")
endif()
set(plugin "${PREFIX}/${PLUGIN_SUBDIR}/GeodesicShapes/GeodesicShapes.so")
if(NOT EXISTS "${plugin}")
  message(FATAL_ERROR "no plugin at ${plugin}")
endif()
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${PREFIX}/${PYTHON_DESTINATION}"
    "${PYTHON}" -c "import geodesicshapes as gs, numpy; print(gs.__file__); v = numpy.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]); f = numpy.array([[0, 1, 2], [1, 3, 2]]); d = gs.geodesic_distance((v, f), 0, solver='exact'); assert abs(d[3] - 2 ** 0.5) < 1e-12, d; print('installed package OK', d)"
  WORKING_DIRECTORY "${PREFIX}"
  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT result EQUAL 0 OR NOT out MATCHES "installed package OK" OR NOT out MATCHES "${PREFIX}")
  message(FATAL_ERROR "the installed package did not run from ${PREFIX}")
endif()
