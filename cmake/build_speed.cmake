# Compile-time measures (a clean build on two cores is most of the CI run: docs/results/build_time.md).
#
# Unity builds: the library folders whose files all parse the same heavy headers (toml11,
# nlohmann_json, Eigen), whose parsing dominates each translation unit, compile in
# batches of SEEDCAL_UNITY_BATCH files. The DEM engine (seedcal_solver) stays one file per unit:
# it is where the time goes into code generation, not parsing.
#
# Precompiled header for the tests: every test executable is one file that parses GoogleTest,
# nlohmann_json and Eigen; they share one precompiled header (seedcal_test_pch). A precompiled
# header is only used by units compiled with the same macros, so every test gets the same
# definitions and OpenMP flag (seedcal_test_env) whatever it links.
option(SEEDCAL_UNITY "Compile the I/O, statistics and pipeline libraries in unity batches" ON)
set(SEEDCAL_UNITY_BATCH 8 CACHE STRING "Files per unity batch")
option(SEEDCAL_PCH "Share one precompiled header between the test executables" ON)
option(SEEDCAL_SLOW_TESTS "Build the tests labelled slow (the sanitizer preset leaves them out)" ON)

# seedcal_unity_build(target [BATCH n]): n files per batch, SEEDCAL_UNITY_BATCH by default.
function(seedcal_unity_build target)
  cmake_parse_arguments(U "" "BATCH" "" ${ARGN})
  if(NOT U_BATCH)
    set(U_BATCH ${SEEDCAL_UNITY_BATCH})
  endif()
  if(SEEDCAL_UNITY)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${U_BATCH})
  endif()
endfunction()

# Sanitizer builds (clang, -O1 by default): the store and report code, which only reads and writes
# files, compiles at -O0, which compiles faster and costs that code nothing at run time. Code that
# does arithmetic on Eigen vectors (the DEM engine, doe/, the clump builders in calibrate/, the
# tests) keeps -O1: at -O0 under ASan it runs several times slower (docs/results/build_time.md).
function(seedcal_sanitizer_o0 target)
  if(SEEDCAL_SANITIZE OR SEEDCAL_FUZZ)
    target_compile_options(${target} PRIVATE -O0)
  endif()
endfunction()
