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

# birotor_add_test(NAME name SOURCES a.cc b.cc LIBS lib1 lib2 [LABELS l] [SOURCE_TREE] [RUN_SERIAL])
# One GoogleTest executable registered with CTest through gtest_discover_tests.
# SOURCE_TREE: the test reads files of the source tree (config/, tests/data/)
# through BIROTOR_SOURCE_DIR; programs and libraries never get that path.
function(birotor_add_test)
  cmake_parse_arguments(T "SOURCE_TREE;RUN_SERIAL" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main birotor_warnings)
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
  gtest_discover_tests(${T_NAME}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES TIMEOUT ${T_TIMEOUT} LABELS "${T_LABELS}" RUN_SERIAL ${serial}
    DISCOVERY_TIMEOUT 60)
endfunction()
