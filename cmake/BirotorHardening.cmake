# Hardening of every compiled target (issue 37), the flags Debian's
# dpkg-buildflags gives with hardening=+all: stack protector on functions
# with arrays or address-taken locals, FORTIFY_SOURCE checks on the libc
# calls whose buffer size is known at compile time (needs optimisation, so
# not in Debug; not under the sanitizers, which replace those calls), position-
# independent executables (ASLR) and a read-only relocation table bound at
# start (full RELRO, BIND_NOW). tests/deploy/hardening_test.sh checks every
# installed program with readelf. None of these touches floating point.
# Every program links only the shared libraries it uses (--as-needed, GCC's
# default on Debian, not clang's): a daemon that maps Ceres, glog and
# SuiteSparse it never calls starts with twice the resident memory.
add_link_options(LINKER:--as-needed)

option(BIROTOR_HARDEN "Build with stack protector, FORTIFY_SOURCE, PIE and full RELRO" ON)
if(NOT BIROTOR_HARDEN)
  return()
endif()

include(CheckPIESupported)
check_pie_supported(LANGUAGES C CXX)
set(CMAKE_POSITION_INDEPENDENT_CODE ON)  # -fPIE for programs (and -pie at link), -fPIC for libraries
add_compile_options(-fstack-protector-strong)
if(NOT BIROTOR_SANITIZE)
  # -U first: a compiler that already defines it (Ubuntu's) would warn of a redefinition.
  add_compile_options("$<$<NOT:$<CONFIG:Debug>>:-U_FORTIFY_SOURCE;-D_FORTIFY_SOURCE=2>")
endif()
add_link_options(LINKER:-z,relro LINKER:-z,now)
