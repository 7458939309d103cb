# CTest `cli_gis_module` (and the install test): the fdrmesh command loads the GIS module
# (fdrmesh_gis.so: GDAL, PROJ, netCDF, SQLite) only when a run needs it, from EXPECT_DIR.
#   cmake -DBIN=fdrmesh -DTESTDATA=testdata -DOUT=dir -DEXPECT_DIR=<libdir>/fdrmesh -P gis_module_test.cmake
# The loader's own trace (LD_DEBUG=files, glibc) says which objects the process opened.
file(REAL_PATH ${EXPECT_DIR} EXPECT_DIR)  # the loader names the module by its real path
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
function(fdrmesh_run expect_rc log)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env LD_DEBUG=files ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL expect_rc)
    message(FATAL_ERROR "exit ${rc}, expected ${expect_rc}: ${ARGN}\n${out}\n${err}")
  endif()
  set(${log} "${err}" PARENT_SCOPE)
endfunction()
function(expect_loaded log what yes)
  string(FIND "${log}" "${what}" at)
  if(yes AND at EQUAL -1)
    message(FATAL_ERROR "${what} was not loaded")
  elseif(NOT yes AND NOT at EQUAL -1)
    message(FATAL_ERROR "${what} was loaded by a run that does not need it")
  endif()
endfunction()

# .poly without output meshes (the report JSON is core): no module, no GDAL.
fdrmesh_run(0 log ${BIN} mesh ${TESTDATA}/poly/square10.poly --spacing 1 -q --report ${OUT}/r.json)
expect_loaded("${log}" "fdrmesh_gis.so" NO)
expect_loaded("${log}" "libgdal" NO)
expect_loaded("${log}" "libproj" NO)
if(NOT EXISTS ${OUT}/r.json)
  message(FATAL_ERROR "no report written")
endif()
# Built with jemalloc (src/cli/CMakeLists.txt): the program's allocator is loaded from the start.
if(JEMALLOC)
  expect_loaded("${log}" "libjemalloc" YES)
endif()
# An output mesh needs the writers: the module, from EXPECT_DIR.
fdrmesh_run(0 log ${BIN} mesh ${TESTDATA}/poly/square10.poly --spacing 1 -q -o ${OUT}/s.2dm)
expect_loaded("${log}" "${EXPECT_DIR}/fdrmesh_gis.so" YES)
if(NOT EXISTS ${OUT}/s.2dm)
  message(FATAL_ERROR "no mesh written")
endif()
# A GIS input and `fdrmesh quality` load it too.
fdrmesh_run(0 log ${BIN} mesh ${TESTDATA}/chesapeake/chesapeake_mouth_water.geojson --hmin 2000 -q)
expect_loaded("${log}" "libgdal" YES)
fdrmesh_run(0 log ${BIN} quality ${OUT}/s.2dm --spacing 1 -q)
expect_loaded("${log}" "fdrmesh_gis.so" YES)
# A missing module: exit 1 naming the paths tried; usage errors still come first (exit 2).
fdrmesh_run(1 log ${CMAKE_COMMAND} -E env FDRMESH_GIS_MODULE=${OUT}/none.so
            ${BIN} mesh ${TESTDATA}/poly/square10.poly --spacing 1 -q -o ${OUT}/t.2dm)
string(FIND "${log}" "ERROR 1: this run needs the GIS module fdrmesh_gis.so" at)
string(FIND "${log}" "${OUT}/none.so: not found" at2)
if(at EQUAL -1 OR at2 EQUAL -1 OR EXISTS ${OUT}/t.2dm)
  message(FATAL_ERROR "missing module: wrong message or output left\n${log}")
endif()
fdrmesh_run(2 log ${CMAKE_COMMAND} -E env FDRMESH_GIS_MODULE=${OUT}/none.so
            ${BIN} mesh ${TESTDATA}/poly/square10.poly --spacing 1 -q -o ${OUT}/t.xyz)
fdrmesh_run(0 log ${CMAKE_COMMAND} -E env FDRMESH_GIS_MODULE=${OUT}/none.so
            ${BIN} mesh ${TESTDATA}/poly/square10.poly --spacing 1 -q)
message(STATUS "GIS module loaded only when needed, from ${EXPECT_DIR}")
