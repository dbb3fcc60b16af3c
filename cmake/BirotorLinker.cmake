# The linker of every executable (docs/development.md): the build links 78
# executables, most of them test executables of 10-40 MB of static libraries,
# and mold links them in a fraction of GNU ld's CPU time. BIROTOR_LINKER
# names the linker GCC runs (-fuse-ld=<name>: mold, lld, gold, bfd); empty
# keeps the compiler's default (GNU ld). The default is mold when it is
# installed (Debian package mold, tools/setup.sh), otherwise GNU ld. Every
# linker here keeps the hardening of cmake/BirotorHardening.cmake (PIE, full
# RELRO, BIND_NOW: tests/deploy/hardening_test.sh checks them).
find_program(BIROTOR_MOLD mold)
if(BIROTOR_MOLD)
  set(birotor_default_linker mold)
else()
  set(birotor_default_linker "")
endif()
set(BIROTOR_LINKER "${birotor_default_linker}" CACHE STRING "Linker GCC runs (-fuse-ld=): mold, lld, gold, bfd; empty for the default")
if(BIROTOR_LINKER)
  add_link_options(-fuse-ld=${BIROTOR_LINKER})
endif()
