# seedcal_add_test(NAME name SOURCES a.cpp ... LIBS lib ... [LABELS l ...] [TIMEOUT s] [COST s] [CASES c ...])
# Tests are listed explicitly, one call per test executable. Labels used by scripts/test.sh:
#   unit, physics, regression, cli, slow (left out of the sanitizer stage).
# CASES: one ctest entry per listed gtest test suite (NAME_suite, run with --gtest_filter=suite.*)
# instead of one for the executable, so that `ctest -j` runs long cases side by side.
# COST: the entry's expected seconds in Release. `ctest -j` starts the costliest entries first; it
# learns the costs after a run, but a clean clone (CI) has none and would start the longest last.

# What every test compiles with (cmake/build_speed.cmake): the same macros whatever it links, so
# that all of them can use seedcal_test_pch.
add_library(seedcal_test_env INTERFACE)
target_link_libraries(seedcal_test_env INTERFACE GTest::gtest OpenMP::OpenMP_CXX Eigen3::Eigen
                      nlohmann_json::nlohmann_json)
target_compile_definitions(seedcal_test_env INTERFACE
                           $<TARGET_PROPERTY:NLopt::nlopt,INTERFACE_COMPILE_DEFINITIONS>
                           $<$<BOOL:${MPI_CXX_FOUND}>:SEEDCAL_HAVE_MPI=1>)
if(SEEDCAL_PCH)
  add_library(seedcal_test_pch OBJECT ${PROJECT_SOURCE_DIR}/cmake/test_pch.cpp)
  target_link_libraries(seedcal_test_pch PRIVATE seedcal_test_env seedcal_warnings)
  target_precompile_headers(seedcal_test_pch PRIVATE
    <gtest/gtest.h> <nlohmann/json.hpp> <Eigen/Dense>
    <algorithm> <cmath> <cstdio> <filesystem> <fstream> <map> <memory> <sstream> <string> <vector>)
endif()

function(seedcal_add_test)
  cmake_parse_arguments(T "" "NAME;TIMEOUT;COST" "SOURCES;LIBS;LABELS;CASES" ${ARGN})
  # The sanitizer build (preset asan) runs `ctest -LE slow`: it does not build the slow tests either.
  if(NOT SEEDCAL_SLOW_TESTS AND "slow" IN_LIST T_LABELS)
    return()
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} seedcal_test_env GTest::gtest_main seedcal_warnings)
  if(SEEDCAL_PCH)
    target_precompile_headers(${T_NAME} REUSE_FROM seedcal_test_pch)
  endif()
  target_include_directories(${T_NAME} PRIVATE ${PROJECT_SOURCE_DIR})
  set_target_properties(${T_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  # End-to-end tests run the binary: build it first.
  add_dependencies(${T_NAME} seedcal)
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 600)
  endif()
  set(entries "")
  if(T_CASES)
    foreach(c IN LISTS T_CASES)
      add_test(NAME ${T_NAME}_${c} COMMAND ${T_NAME} --gtest_filter=${c}.* WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
      list(APPEND entries ${T_NAME}_${c})
    endforeach()
  else()
    add_test(NAME ${T_NAME} COMMAND ${T_NAME} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    set(entries ${T_NAME})
  endif()
  # A GTEST_SKIP shows as skipped, not passed; a filter that matches no test fails (GoogleTest 1.12
  # exits 0 on it and has no flag against it).
  set_tests_properties(${entries} PROPERTIES SKIP_REGULAR_EXPRESSION "\\[  SKIPPED \\]"
                       FAIL_REGULAR_EXPRESSION "\\[==========\\] 0 tests from 0 test suites ran")
  set_tests_properties(${entries} PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT}
                       ENVIRONMENT "SEEDCAL_SOURCE_DIR=${PROJECT_SOURCE_DIR};SEEDCAL_BINARY=${CMAKE_BINARY_DIR}/seedcal")
  if(T_COST)
    set_tests_properties(${entries} PROPERTIES COST ${T_COST})
  endif()
endfunction()
