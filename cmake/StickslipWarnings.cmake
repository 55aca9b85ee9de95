# Flags for stickslip's own targets (tests, examples, benchmarks) only; never for consumers.
add_library(stickslip_project_options INTERFACE)
target_compile_options(stickslip_project_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion
  # Clang's -Wconversion includes -Wsign-conversion, GCC's (C++) does not: one warning set for both.
  $<$<CXX_COMPILER_ID:Clang>:-Wno-sign-conversion>
  $<$<BOOL:${STICKSLIP_WARNINGS_AS_ERRORS}>:-Werror>)
if(STICKSLIP_SANITIZE)
  target_compile_options(stickslip_project_options INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  # Lets a test scale down its longest cases under the sanitizers (it says which and why).
  target_compile_definitions(stickslip_project_options INTERFACE STICKSLIP_SANITIZED)
  target_link_options(stickslip_project_options INTERFACE -fsanitize=address,undefined)
endif()
target_link_libraries(stickslip_project_options INTERFACE stickslip::stickslip)

option(STICKSLIP_TEST_PCH
       "Precompile GoogleTest, Eigen and stickslip's umbrella header once for the test executables" ON)

# stickslip_add_gtest(<name> LABEL <label> SOURCES <files...> [FULL_SIZE_SOURCES <files...>]
#                     [TIMEOUT s] [NO_UNITY] [NO_PCH] [LIGHT_RUN])
# One GoogleTest executable whose tests CTest discovers, each carrying the component label.
# With STICKSLIP_UNITY_TESTS (default ON) its sources compile as one unity translation unit,
# unless NO_UNITY (sources whose file-local names clash). With STICKSLIP_TEST_PCH (default ON) it
# reuses one precompiled header of GoogleTest + <stickslip/stickslip.hpp>, unless NO_PCH (sources
# that must define macros before Eigen is included, e.g. EIGEN_RUNTIME_NO_MALLOC).
# LIGHT_RUN: the executable's tests run in well under two seconds at -O1 (measured, ASan + UBSan).
# In the sanitizer build (STICKSLIP_SANITIZE) it is then compiled at -O0: Clang compiles an
# instrumented unit ~2.7x faster there (model_test: 49 s against 132 s of CPU) and the
# sanitizers see every access the source makes, while the tests run ~8x slower, which only
# executables with light runs can afford (model_test's runs took 330 s instead of 40 s).
# FULL_SIZE_SOURCES: the sources (a subset of SOURCES) whose cases the sanitizer build scales down
# or leaves out (STICKSLIP_SANITIZED). With STICKSLIP_TEST_SPLIT (scripts/test.sh's two builds),
# every unit test runs once, in the AddressSanitizer + UBSan build, which checks the same numbers
# and memory and undefined behaviour too; the normal build compiles only the FULL_SIZE_SOURCES
# (and no executable without them), so that the full-size cases still run, optimised and
# uninstrumented. That halves the normal build's compilation. Without STICKSLIP_TEST_SPLIT (the
# default, e.g. ctest in one's own build tree) every executable has all its sources.
function(stickslip_add_gtest name)
  cmake_parse_arguments(ARG "NO_UNITY;NO_PCH;LIGHT_RUN" "LABEL;TIMEOUT" "SOURCES;FULL_SIZE_SOURCES" ${ARGN})
  foreach(source IN LISTS ARG_FULL_SIZE_SOURCES)
    if(NOT source IN_LIST ARG_SOURCES)
      message(FATAL_ERROR "stickslip_add_gtest(${name}): FULL_SIZE_SOURCES ${source} is not in SOURCES")
    endif()
  endforeach()
  if(STICKSLIP_TEST_SPLIT AND NOT STICKSLIP_SANITIZE)
    if(NOT ARG_FULL_SIZE_SOURCES)
      # Left out of `all` and of CTest, but defined, so that the directory's further target_*()
      # calls on it stay valid and `cmake --build . --target <name>` still builds it.
      add_executable(${name} EXCLUDE_FROM_ALL ${ARG_SOURCES})
      target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
      target_link_libraries(${name} PRIVATE stickslip_project_options ${STICKSLIP_OWN_TARGET} GTest::gtest
                                            GTest::gtest_main)
      return()
    endif()
    set(ARG_SOURCES ${ARG_FULL_SIZE_SOURCES})
  endif()
  set(unoptimised OFF)
  if(STICKSLIP_SANITIZE AND ARG_LIGHT_RUN)
    set(unoptimised ON)
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  if(STICKSLIP_UNITY_TESTS AND NOT ARG_NO_UNITY)
    # All sources of one test executable in one translation unit: Eigen and GoogleTest are parsed
    # and instantiated once instead of once per file (test files keep their helpers in named or
    # per-file namespaces so that they can share the unit).
    set_target_properties(${name} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 0)
  endif()
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  target_link_libraries(${name} PRIVATE stickslip_project_options ${STICKSLIP_OWN_TARGET} GTest::gtest
                                        GTest::gtest_main)
  set(pch stickslip_test_pch)
  if(unoptimised)
    target_compile_options(${name} PRIVATE -O0)  # after the build type's -O1: the last one wins
    set(pch stickslip_test_pch_O0)  # a header precompiled at -O1 does not match an -O0 unit
  endif()
  if(STICKSLIP_TEST_PCH AND NOT ARG_NO_PCH)
    if(NOT TARGET ${pch})
      # The header is parsed once per build instead of once per test executable (~2-3 s each).
      file(CONFIGURE OUTPUT ${PROJECT_BINARY_DIR}/${pch}.cpp
           CONTENT "// precompiled header of the test executables\n")
      add_library(${pch} OBJECT ${PROJECT_BINARY_DIR}/${pch}.cpp)
      target_link_libraries(${pch} PRIVATE stickslip_project_options ${STICKSLIP_OWN_TARGET} GTest::gtest)
      if(unoptimised)
        target_compile_options(${pch} PRIVATE -O0)
      endif()
      target_precompile_headers(${pch} PRIVATE <gtest/gtest.h> <stickslip/stickslip.hpp>)
    endif()
    target_precompile_headers(${name} REUSE_FROM ${pch})
  endif()
  gtest_discover_tests(${name} PROPERTIES LABELS ${ARG_LABEL} TIMEOUT ${ARG_TIMEOUT}
                       DISCOVERY_TIMEOUT 60)
  # The measured costs of the longest tests (tests/test_costs.cmake), read after every discovered
  # test of this directory exists: appended once, at the end of the directory's CMakeLists.txt.
  get_property(costs_added DIRECTORY PROPERTY STICKSLIP_TEST_COSTS_ADDED)
  if(NOT costs_added)
    set_property(DIRECTORY PROPERTY STICKSLIP_TEST_COSTS_ADDED ON)
    cmake_language(DEFER CALL set_property DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES
                   "${PROJECT_SOURCE_DIR}/tests/test_costs.cmake")
  endif()
endfunction()
