# dlslam_module(NAME SOURCES a.cc b.cc DEPS dlslam::util ... TESTS a_test.cc
#               [TEST_DEPS ...] [BENCHMARKS a_bench.cc] [BENCHMARK_DEPS ...])
#   One static library per folder of src/dlslam (header-only when it has no
#   SOURCES), aliased dlslam::NAME, with its unit tests (NAME_test) and
#   Google Benchmarks (bin/dlslam_bench_NAME) side by side.
function(dlslam_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;TESTS;TEST_DEPS;BENCHMARKS;BENCHMARK_DEPS" ${ARGN})
  set(target dlslam_${name})
  if(ARG_SOURCES)
    add_library(${target} STATIC ${ARG_SOURCES})
    target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(${target} PUBLIC ${ARG_DEPS})
    dlslam_set_compiler_options(${target})
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  add_library(dlslam::${name} ALIAS ${target})
  if(DLSLAM_BUILD_TESTS AND ARG_TESTS)
    dlslam_test(${name}_test SOURCES ${ARG_TESTS} DEPS ${target} ${ARG_TEST_DEPS})
  endif()
  if(DLSLAM_BUILD_BENCHMARKS AND ARG_BENCHMARKS)
    dlslam_benchmark(dlslam_bench_${name} SOURCES ${ARG_BENCHMARKS} DEPS ${target} ${ARG_BENCHMARK_DEPS})
  endif()
endfunction()

# dlslam_test(NAME SOURCES ... DEPS ...): a GoogleTest executable whose tests
# are discovered when ctest runs (not at build time, so sanitizer builds and
# cross builds stay cheap).
function(dlslam_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} dlslam_test_support GTest::gtest_main GTest::gmock)
  dlslam_set_compiler_options(${name})
  gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST
    PROPERTIES ENVIRONMENT "DLSLAM_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()

# dlslam_benchmark(NAME SOURCES ... DEPS ...): a Google Benchmark executable.
function(dlslam_benchmark name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} benchmark::benchmark_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/src)
  dlslam_set_compiler_options(${name})
endfunction()
