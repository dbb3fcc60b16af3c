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

# birotor_add_test(NAME name SOURCES a.cc b.cc LIBS lib1 lib2 [LABELS l])
# One GoogleTest executable registered with CTest through gtest_discover_tests.
function(birotor_add_test)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main birotor_warnings)
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  gtest_discover_tests(${T_NAME}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES TIMEOUT ${T_TIMEOUT} LABELS "${T_LABELS}"
    DISCOVERY_TIMEOUT 60)
endfunction()
