# The Python module's tests (pytest, one ctest test per file): included by tests/CMakeLists.txt when the module is
# built (python/CMakeLists.txt). They import the module from the build folder with the interpreter it was built for,
# and compare with the programs built beside it. Without pytest they are skipped (scripts/install-deps.sh --python
# installs it), unless BLOCKDEM_REQUIRE_PYTHON_TESTS is set in the environment (CI).
set(python_test_env
  "PYTHONPATH=${BLOCKDEM_PYTHON_DIR}"
  "BLOCKDEM_PROGRAMS=${PROJECT_BINARY_DIR}/examples"
  "BLOCKDEM_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
  "BLOCKDEM_SHARED_DATA=${PROJECT_SOURCE_DIR}/../shared/data"
  "BLOCKDEM_BUILD_DIR=${PROJECT_BINARY_DIR}"
  "OMP_NUM_THREADS=1")
file(MAKE_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}/python")  # pytest's --basetemp makes only the last folder
foreach(name damping motion model study simulation sweep examples install)
  add_test(NAME python.${name}
    COMMAND ${BLOCKDEM_PYTHON_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/run_pytest.py
            ${CMAKE_CURRENT_SOURCE_DIR}/python/test_${name}.py --basetemp=${CMAKE_CURRENT_BINARY_DIR}/python/${name})
  set_tests_properties(python.${name} PROPERTIES ENVIRONMENT "${python_test_env}" SKIP_RETURN_CODE 77 TIMEOUT 600)
endforeach()
