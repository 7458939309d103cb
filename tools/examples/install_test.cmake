# CTest `install_consumer`: cmake --install into a temporary prefix, then configure, build and run
# tools/examples against it with find_package(fdrmesh).
# -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DWITH_GIS=ON|OFF -DGENERATOR=...
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tools/examples -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build -j 2)
run(${WORK_DIR}/build/triangulate_example)
run(${WORK_DIR}/build/triangulate_example ${SOURCE_DIR}/testdata/poly/square_with_hole.poly)
if(WITH_GIS)
  run(${WORK_DIR}/build/mesh_domain_example ${SOURCE_DIR}/testdata/poly/square10.poly 1 ${WORK_DIR}/square.2dm)
  if(NOT EXISTS ${WORK_DIR}/square.2dm)
    message(FATAL_ERROR "mesh_domain_example wrote no ${WORK_DIR}/square.2dm")
  endif()
  # The installed fdrmesh command loads its GIS module from the prefix, and only when needed.
  run(${CMAKE_COMMAND} -DBIN=${prefix}/bin/fdrmesh -DTESTDATA=${SOURCE_DIR}/testdata -DOUT=${WORK_DIR}/gis_module
      -DEXPECT_DIR=${prefix}/${LIBDIR}/fdrmesh -P ${SOURCE_DIR}/src/cli/tests/gis_module_test.cmake)
endif()
