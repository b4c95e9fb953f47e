# ctest runs each test case of the test binary by its name. A name with ';' is split in two by the discovery
# (CMake lists), and neither half matches a test case: both run nothing and pass. This check fails on such a name.
#   cmake -DTEST_BINARY=path -P check_test_names.cmake
execute_process(COMMAND "${TEST_BINARY}" --list-test-cases --no-version RESULT_VARIABLE status OUTPUT_VARIABLE out)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${TEST_BINARY} --list-test-cases failed (${status})")
endif()
string(REGEX MATCH "[^\n]*;[^\n]*" named "${out}")
if(named)
  message(FATAL_ERROR "a test case name holds ';', which ctest splits into two tests that run nothing: '${named}'")
endif()
string(REGEX MATCHALL "\n" lines "${out}")
list(LENGTH lines count)
message(STATUS "${count} lines of test case names, none with ';'")
