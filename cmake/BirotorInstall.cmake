# What `cmake --install build --prefix PREFIX` puts in place besides the
# programs: the reference files the programs find as defaults
# (PREFIX/share/birotor/config, see transport/config_files.h), the .lcm
# files, the Python package `birotor`, the systemd units and their
# environment file with PREFIX written in at install time, and the lcm-spy
# launcher. No installed file names the source or build tree.
#
# The Debian package (`cpack -G DEB` in the build directory; docs/deploy.md)
# adds the component `debian`, which a plain `cmake --install` leaves out:
# the site files in /etc/birotor and /etc/default/birotor (conffiles) and the
# units in PREFIX/lib/systemd/system.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION share/birotor/config)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/tools/lcm-spy.sh DESTINATION bin RENAME birotor-lcm-spy)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/lcmtypes/ DESTINATION share/birotor/lcmtypes FILES_MATCHING PATTERN "*.lcm")

set(BIROTOR_DEPLOY_FILES birotor-estimator.service birotor-controller.service birotor-sim.service birotor.env)
# configure_file at install time, so a `--prefix` given to cmake --install is
# the one written into the units; each unit's @BIROTOR_UNIT_SANDBOX@ line
# becomes the sandbox shared by all (deploy/unit-sandbox.conf).
function(birotor_install_configured source target component)
  install(CODE "
    set(deploy_target \"\$ENV{DESTDIR}${target}\")
    message(STATUS \"Installing: \${deploy_target}\")
    file(READ \"${PROJECT_SOURCE_DIR}/deploy/unit-sandbox.conf\" BIROTOR_UNIT_SANDBOX)
    string(STRIP \"\${BIROTOR_UNIT_SANDBOX}\" BIROTOR_UNIT_SANDBOX)
    configure_file(\"${PROJECT_SOURCE_DIR}/deploy/${source}.in\" \"\${deploy_target}\" @ONLY)
  " COMPONENT ${component} ${ARGN})
endfunction()
foreach(deploy_file ${BIROTOR_DEPLOY_FILES})
  birotor_install_configured(${deploy_file} "\${CMAKE_INSTALL_PREFIX}/share/birotor/deploy/${deploy_file}" Unspecified)
endforeach()

# The package's site files. estimator.yaml keeps the learned gauge offsets in
# the unit's StateDirectory; otherwise the conffiles are the shipped files.
set(BIROTOR_STATE_FILE /var/lib/birotor/gauge_offsets.yaml)
file(READ ${PROJECT_SOURCE_DIR}/config/estimator.yaml site_estimator)
# Re-configure when it changes, so the site file never lags behind it.
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/config/estimator.yaml)
string(FIND "${site_estimator}" "state_file: \"\"" state_key_at)
if(state_key_at LESS 0)
  message(FATAL_ERROR "config/estimator.yaml has no `state_file: \"\"` line for the package to set")
endif()
string(REPLACE "state_file: \"\"" "state_file: ${BIROTOR_STATE_FILE}" site_estimator "${site_estimator}")
file(WRITE ${CMAKE_BINARY_DIR}/deploy/etc/estimator.yaml "${site_estimator}")
set(BIROTOR_CONFFILES estimator.yaml controller.yaml identification.yaml reference_vehicle.yaml)
install(FILES ${CMAKE_BINARY_DIR}/deploy/etc/estimator.yaml ${PROJECT_SOURCE_DIR}/config/controller.yaml
              ${PROJECT_SOURCE_DIR}/config/identification.yaml ${PROJECT_SOURCE_DIR}/config/reference_vehicle.yaml
        DESTINATION /etc/birotor COMPONENT debian EXCLUDE_FROM_ALL)
birotor_install_configured(birotor.env /etc/default/birotor debian EXCLUDE_FROM_ALL)
foreach(unit birotor-estimator.service birotor-controller.service birotor-sim.service)
  birotor_install_configured(${unit} "\${CMAKE_INSTALL_PREFIX}/lib/systemd/system/${unit}" debian EXCLUDE_FROM_ALL)
endforeach()
# The socket buffer the units' LCM URL asks for (net.core.rmem_max).
install(FILES ${PROJECT_SOURCE_DIR}/deploy/60-birotor.conf DESTINATION lib/sysctl.d
        COMPONENT debian EXCLUDE_FROM_ALL)

# The Debian package: birotor_<version>_<arch>.deb, every component in one.
set(conffiles "")
foreach(name ${BIROTOR_CONFFILES})
  string(APPEND conffiles "/etc/birotor/${name}\n")
endforeach()
string(APPEND conffiles "/etc/default/birotor\n")
file(WRITE ${CMAKE_BINARY_DIR}/deploy/control/conffiles "${conffiles}")
foreach(script postinst prerm postrm)
  file(COPY ${PROJECT_SOURCE_DIR}/deploy/${script} DESTINATION ${CMAKE_BINARY_DIR}/deploy/control
       FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
endforeach()
include(${PROJECT_SOURCE_DIR}/cmake/BirotorDocs.cmake)
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME birotor)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
# A placeholder address (example.org): lintian refuses one on localhost.
set(CPACK_PACKAGE_CONTACT "The birotor developers <birotor@example.org>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Rotor-force estimation and control for a strain-gauged birotor over LCM")
# Lines under 80 characters (lintian extended-description-line-too-long).
set(CPACK_PACKAGE_DESCRIPTION
    "The estimator and controller daemons with their systemd units, the simulator,\n\
identification, replay, review and export tools, the LCM types (.lcm, Java jar\n\
for lcm-spy, Python package birotor).")
# /usr for the programs, DESTDIR staging so /etc/birotor lands in the package.
set(CPACK_SET_DESTDIR ON)
set(CPACK_STRIP_FILES ON)
set(CPACK_INSTALL_PREFIX /usr)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_COMPONENTS_ALL Unspecified debian)
set(CPACK_DEBIAN_PACKAGE_NAME birotor)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, systemd")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-pandas, liblcm-java, default-jre-headless, gnuplot-nox")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    "${CMAKE_BINARY_DIR}/deploy/control/conffiles;${CMAKE_BINARY_DIR}/deploy/control/postinst;\
${CMAKE_BINARY_DIR}/deploy/control/prerm;${CMAKE_BINARY_DIR}/deploy/control/postrm")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
