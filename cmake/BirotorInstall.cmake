# What `cmake --install build --prefix PREFIX` puts in place besides the
# programs: the reference files the programs find as defaults
# (PREFIX/share/birotor/config, see transport/config_files.h), the systemd
# units and their environment file with PREFIX written in at install time,
# and the lcm-spy launcher. No installed file names the source or build tree.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION share/birotor/config)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/tools/lcm-spy.sh DESTINATION bin RENAME birotor-lcm-spy)

# configure_file at install time, so a `--prefix` given to cmake --install is
# the one written into the units.
foreach(deploy_file birotor-estimator.service birotor-controller.service birotor-sim.service birotor.env)
  install(CODE "
    set(deploy_target \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/share/birotor/deploy/${deploy_file}\")
    message(STATUS \"Installing: \${deploy_target}\")
    configure_file(\"${PROJECT_SOURCE_DIR}/deploy/${deploy_file}.in\" \"\${deploy_target}\" @ONLY)
  ")
endforeach()
