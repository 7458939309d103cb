# PostGIS against a real server: CTest's fixture starts a throw-away PostgreSQL + PostGIS cluster
# (tools/postgis/cluster.sh) before the tests that need it and removes it after. When the server
# cannot start here, the fixture still passes and writes why; the tests then skip saying so.
if(NOT FDR_BUILD_TESTS)
  return()
endif()
set(FDR_PG_STATE ${CMAKE_BINARY_DIR}/postgis)
add_test(NAME postgis_server_start COMMAND bash ${PROJECT_SOURCE_DIR}/tools/postgis/cluster.sh start ${FDR_PG_STATE})
add_test(NAME postgis_server_stop COMMAND bash ${PROJECT_SOURCE_DIR}/tools/postgis/cluster.sh stop ${FDR_PG_STATE})
set_tests_properties(postgis_server_start PROPERTIES FIXTURES_SETUP postgis_server RESOURCE_LOCK postgis_server TIMEOUT 120)
set_tests_properties(postgis_server_stop PROPERTIES FIXTURES_CLEANUP postgis_server RESOURCE_LOCK postgis_server)

# The writer (one transaction, failure hook, --overwrite, errors without passwords): GoogleTest.
add_executable(postgis_tests ${CMAKE_CURRENT_SOURCE_DIR}/tests/postgis_test.cpp)
target_link_libraries(postgis_tests PRIVATE fdr_io GDAL::GDAL GTest::gtest GTest::gtest_main)
target_compile_definitions(postgis_tests PRIVATE FDR_PG_STATE="${FDR_PG_STATE}")
add_test(NAME postgis_writer COMMAND postgis_tests)
set_tests_properties(postgis_writer PROPERTIES FIXTURES_REQUIRED postgis_server RESOURCE_LOCK postgis_db
                     SKIP_REGULAR_EXPRESSION "PostgreSQL test server not available")
# The same on one thread: the staged load's two sides on one connection, one after the other.
add_test(NAME postgis_writer_one_thread
         COMMAND postgis_tests --gtest_filter=Postgis.WritesTheGeoPackageTables:Postgis.FailureAtEachStepLeavesNothing)
set_tests_properties(postgis_writer_one_thread PROPERTIES FIXTURES_REQUIRED postgis_server RESOURCE_LOCK postgis_db
                     ENVIRONMENT "FDR_THREADS=1" SKIP_REGULAR_EXPRESSION "PostgreSQL test server not available")

# The command line in and out of the database (pytest): same 2DM as from the GeoPackage,
# read back with ogr and SQL, exit codes and messages.
add_test(NAME postgis_cli
         COMMAND /bin/sh -c "/usr/bin/python3 -c 'import pytest' 2>/dev/null || exit 77; exec /usr/bin/python3 -m pytest -q -rs -p no:cacheprovider \"$0\"" ${CMAKE_CURRENT_SOURCE_DIR}/tests/test_postgis.py)
set_tests_properties(postgis_cli PROPERTIES FIXTURES_REQUIRED postgis_server RESOURCE_LOCK postgis_db SKIP_RETURN_CODE 77
                     SKIP_REGULAR_EXPRESSION "PostgreSQL test server not available"
                     ENVIRONMENT "FDRMESH=$<TARGET_FILE:fdrmesh>;FDR_PG_STATE=${FDR_PG_STATE};FDR_TESTDATA=${PROJECT_SOURCE_DIR}/testdata;PYTHONPATH=${PROJECT_BINARY_DIR}/python;PYTHONDONTWRITEBYTECODE=1")
