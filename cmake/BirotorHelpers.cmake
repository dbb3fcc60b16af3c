# Small helpers shared by every folder.
#
# Naming: an installed program's target is its file name (birotor-sim,
# birotor-estimator, ...); libraries are birotor_<folder>; test, benchmark and
# fuzz executables are named after their source file (model_test,
# estimator_benchmark, decode_fuzzer).

# Warnings for our own code only (not for dependencies' headers): every
# birotor target links birotor_warnings PRIVATE.
add_library(birotor_warnings INTERFACE)
target_compile_options(birotor_warnings INTERFACE -Wall -Wextra)

# Build time of the tests (docs/development.md): test sources are most of the
# translation units and mostly front-end work (parsing GoogleTest, Eigen and
# the standard library), so every test executable reuses one precompiled
# header of those, made once by birotor_test_pch. Test sources compile at
# BIROTOR_TEST_OPTIMIZATION (the libraries and programs they link keep the
# Release -O3, so the simulations a test runs keep their speed).
set(BIROTOR_TEST_OPTIMIZATION "-O1" CACHE STRING "Optimisation flag of the test sources (not of the libraries they test)")
option(BIROTOR_TEST_PCH "Test executables share one precompiled header (GoogleTest, Eigen, std)" ON)
set(BIROTOR_TEST_PCH_HEADERS <gtest/gtest.h> <Eigen/Core> <Eigen/Geometry> <algorithm> <cmath> <cstdint> <cstdio>
    <cstdlib> <fstream> <functional> <limits> <map> <memory> <random> <sstream> <string> <vector>)

# birotor_test_compile_options(target): the flags every test executable shares
# (they must match for the shared precompiled header to be valid).
# -pthread for all: GCC ignores a precompiled header made without _REENTRANT
# in a compilation that defines it (most tests get -pthread from lcm anyway).
function(birotor_test_compile_options target)
  target_link_libraries(${target} PRIVATE GTest::gtest Eigen3::Eigen birotor_warnings)
  target_compile_options(${target} PRIVATE -pthread)
  target_link_options(${target} PRIVATE -pthread)
  if(CMAKE_BUILD_TYPE STREQUAL "Release" AND BIROTOR_TEST_OPTIMIZATION)
    # After the Release -O3 on the command line, so it is the one that counts.
    target_compile_options(${target} PRIVATE ${BIROTOR_TEST_OPTIMIZATION})
  endif()
endfunction()

if(BIROTOR_BUILD_TESTS AND BIROTOR_TEST_PCH)
  # An executable, not a library: its -fPIE must match the tests' (GCC
  # refuses a header precompiled with -fPIC in a -fPIE compilation).
  file(WRITE ${CMAKE_BINARY_DIR}/birotor_test_pch.cc "// Makes the tests' precompiled header.\nint main() { return 0; }\n")
  add_executable(birotor_test_pch ${CMAKE_BINARY_DIR}/birotor_test_pch.cc)
  birotor_test_compile_options(birotor_test_pch)
  target_precompile_headers(birotor_test_pch PRIVATE ${BIROTOR_TEST_PCH_HEADERS})
endif()

# Build time of the libraries (docs/development.md): their units compile at
# -O3 and each parsed Eigen, the standard library and, in the programs'
# libraries, fmt, spdlog and LCM again. A library calls
# birotor_library_pch(target [SERVICE]) in its CMakeLists.txt and its units
# reuse a precompiled header of those made once per build:
# - birotor_library_pch: the model-side libraries (model, estimator,
#   controller, simulator, identification, params; 104 units, most on
#   fixed-size Eigen);
# - birotor_service_pch (SERVICE): the libraries of the daemons and tools on
#   spdlog and LCM (program, sources, nodes, replay, evaluation, monitor,
#   plot, review; 62 units).
# clang refuses a precompiled header made with other macros or another
# -fPIC / -fPIE setting, so each maker has the flags of the libraries that
# use it: a static library (-fPIC) with the same usage requirements (Ceres'
# glog definitions, which every library on birotor_model gets; for SERVICE
# also spdlog's and fmt's definitions and LCM's -pthread). A library with
# other flags must not use it (clang stops with "definition of macro ...
# differs"; GCC silently ignores a header that does not fit: -Winvalid-pch).
# Only headers that every unit parses the same way and that define no object
# (no <iostream>, so no static initialiser is added): what a program computes
# does not change (the same instructions with and without it; only the order
# of local symbols may differ).
option(BIROTOR_LIBRARY_PCH "Libraries share precompiled headers (Eigen, std; fmt, spdlog, LCM)" ON)
set(BIROTOR_LIBRARY_PCH_HEADERS <Eigen/Core> <algorithm> <array> <cmath> <cstdint> <limits> <memory> <string> <vector>)
set(BIROTOR_SERVICE_PCH_HEADERS ${BIROTOR_LIBRARY_PCH_HEADERS} <fmt/format.h> <spdlog/spdlog.h> <lcm/lcm-cpp.hpp>
    <string_view>)
if(BIROTOR_LIBRARY_PCH)
  file(WRITE ${CMAKE_BINARY_DIR}/birotor_library_pch.cc "// Makes a precompiled header of the libraries.\n")
  add_library(birotor_library_pch STATIC ${CMAKE_BINARY_DIR}/birotor_library_pch.cc)
  target_link_libraries(birotor_library_pch PRIVATE Eigen3::Eigen Ceres::ceres birotor_warnings)
  target_precompile_headers(birotor_library_pch PRIVATE ${BIROTOR_LIBRARY_PCH_HEADERS})
  add_library(birotor_service_pch STATIC ${CMAKE_BINARY_DIR}/birotor_library_pch.cc)
  target_link_libraries(birotor_service_pch PRIVATE Eigen3::Eigen Ceres::ceres spdlog::spdlog PkgConfig::LCM
                        birotor_warnings)
  target_precompile_headers(birotor_service_pch PRIVATE ${BIROTOR_SERVICE_PCH_HEADERS})
endif()

# birotor_library_pch(target [SERVICE]): the library's units reuse that header.
function(birotor_library_pch target)
  if(NOT TARGET birotor_library_pch)
    return()
  endif()
  if("${ARGN}" STREQUAL "SERVICE")
    target_precompile_headers(${target} REUSE_FROM birotor_service_pch)
  else()
    target_precompile_headers(${target} REUSE_FROM birotor_library_pch)
  endif()
endfunction()

# birotor_add_test(NAME name SOURCES a.cc b.cc LIBS lib1 lib2 [LABELS l] [SOURCE_TREE] [RUN_SERIAL]
#                  [TIMEOUT s] [COST s])
# One GoogleTest executable registered with CTest through gtest_discover_tests.
# SOURCE_TREE: the test reads files of the source tree (config/, tests/data/)
# through BIROTOR_SOURCE_DIR; programs and libraries never get that path.
function(birotor_add_test)
  cmake_parse_arguments(T "SOURCE_TREE;RUN_SERIAL" "NAME;TIMEOUT;COST" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main birotor_warnings)
  birotor_test_compile_options(${T_NAME})
  if(TARGET birotor_test_pch)
    target_precompile_headers(${T_NAME} REUSE_FROM birotor_test_pch)
  endif()
  if(T_SOURCE_TREE)
    target_compile_definitions(${T_NAME} PRIVATE BIROTOR_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  # RUN_SERIAL: tests that fly in real time on the wall clock (live daemons
  # over udpm judged on flight figures) run with nothing else beside them, so
  # a loaded machine does not decide their outcome.
  set(serial FALSE)
  if(T_RUN_SERIAL)
    set(serial TRUE)
  endif()
  # COST: about the seconds one of its tests takes. `ctest -j` starts the
  # costliest first; a fresh build directory has no measured costs
  # (Testing/Temporary/CTestCostData.txt), and a minute-long test started
  # last would leave the other core idle while it ends.
  if(NOT T_COST)
    set(T_COST 0)
  endif()
  # An empty LABELS value would vanish from the list and shift every
  # property after it (LABELS would take the name RUN_SERIAL): only given.
  set(properties TIMEOUT ${T_TIMEOUT} RUN_SERIAL ${serial} COST ${T_COST})
  if(T_LABELS)
    list(APPEND properties LABELS "${T_LABELS}")
  endif()
  gtest_discover_tests(${T_NAME}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES ${properties}
    DISCOVERY_TIMEOUT 60)
endfunction()
