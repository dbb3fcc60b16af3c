# Build time of the programs (docs/development.md): every program's sources
# (tools/, services/) parse the same large headers (CLI11, spdlog with fmt,
# Eigen, LCM, yaml-cpp), about a third of such a unit's compile time. So they
# reuse one precompiled header of those, made once by birotor_program_pch
# (option BIROTOR_PROGRAM_PCH, default ON). Each source still includes what it
# uses: with the option OFF every unit compiles alone.
# The header is valid only in compilations with the same flags: the maker is
# an executable (-fPIE, as the programs) with -pthread, linking what every
# program links for these headers (birotor_program: spdlog, CLI11, LCM).
option(BIROTOR_PROGRAM_PCH "Programs share one precompiled header (CLI11, spdlog, Eigen, LCM, yaml-cpp, std)" ON)
set(BIROTOR_PROGRAM_PCH_HEADERS <CLI/CLI.hpp> <spdlog/spdlog.h> <fmt/format.h> <Eigen/Core> <lcm/lcm-cpp.hpp>
    <yaml-cpp/yaml.h> <algorithm> <cmath> <cstdint> <cstdio> <filesystem> <fstream> <functional> <memory> <optional>
    <sstream> <string> <vector>)

# birotor_program_compile_options(target): the flags the header's maker and
# every program share.
function(birotor_program_compile_options target)
  target_link_libraries(${target} PRIVATE birotor_program yaml-cpp Eigen3::Eigen birotor_warnings)
  target_compile_options(${target} PRIVATE -pthread)
endfunction()

if(BIROTOR_PROGRAM_PCH)
  file(WRITE ${CMAKE_BINARY_DIR}/birotor_program_pch.cc "// Makes the programs' precompiled header.\nint main() { return 0; }\n")
  add_executable(birotor_program_pch ${CMAKE_BINARY_DIR}/birotor_program_pch.cc)
  birotor_program_compile_options(birotor_program_pch)
  target_precompile_headers(birotor_program_pch PRIVATE ${BIROTOR_PROGRAM_PCH_HEADERS})
endif()

# birotor_use_program_pch(dir...): every executable defined in the folders
# reuses the programs' precompiled header.
function(birotor_use_program_pch)
  if(NOT TARGET birotor_program_pch)
    return()
  endif()
  foreach(dir ${ARGN})
    get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target ${targets})
      get_target_property(type ${target} TYPE)
      if(type STREQUAL "EXECUTABLE")
        birotor_program_compile_options(${target})
        target_precompile_headers(${target} REUSE_FROM birotor_program_pch)
      endif()
    endforeach()
  endforeach()
endfunction()
