# The documentation a Debian package carries (lintian; docs/deploy.md):
# /usr/share/doc/birotor/copyright (DEP-5, deploy/copyright), changelog.gz
# (deploy/changelog, gzip -9n; a native package) and a manual page per
# installed program, made at build time from its --help (deploy/man_page.sh,
# help2man). Paths in the pages are the package's, BIROTOR_PACKAGE_PREFIX.
find_program(HELP2MAN help2man REQUIRED)
set(BIROTOR_PACKAGE_PREFIX /usr)
set(doc_dir ${CMAKE_BINARY_DIR}/deploy/doc)
file(MAKE_DIRECTORY ${doc_dir}/man1)

add_custom_command(OUTPUT ${doc_dir}/changelog.gz
  COMMAND gzip -9nc ${PROJECT_SOURCE_DIR}/deploy/changelog > ${doc_dir}/changelog.gz
  DEPENDS ${PROJECT_SOURCE_DIR}/deploy/changelog
  COMMENT "deploy/changelog -> changelog.gz")

# birotor_man_page(NAME FILE DEPENDS...): NAME.1.gz from the program FILE.
set(BIROTOR_MAN_PAGES "")
function(birotor_man_page name file)
  set(page ${doc_dir}/man1/${name}.1.gz)
  add_custom_command(OUTPUT ${page}
    COMMAND sh ${PROJECT_SOURCE_DIR}/deploy/man_page.sh ${page} ${file} ${name} ${PROJECT_VERSION}
            ${CMAKE_BINARY_DIR} ${BIROTOR_PACKAGE_PREFIX}
    DEPENDS ${ARGN} ${PROJECT_SOURCE_DIR}/deploy/man_page.sh
    COMMENT "help2man: ${name}.1.gz")
  set(BIROTOR_MAN_PAGES ${BIROTOR_MAN_PAGES} ${page} PARENT_SCOPE)
endfunction()
# Every program installed in bin (package_test.sh checks that each has its page).
foreach(program birotor-sim birotor-estimator birotor-controller birotor-analyze birotor-review birotor-replay
                birotor-eval birotor-plot birotor-latency-probe birotor-identify birotor-monitor birotor-soak-monitor)
  birotor_man_page(${program} $<TARGET_FILE:${program}> ${program})
endforeach()
birotor_man_page(birotor-export ${CMAKE_BINARY_DIR}/python/birotor-export birotor_python)
set(spy_depends ${PROJECT_SOURCE_DIR}/tools/lcm-spy.sh)
if(TARGET birotor_lcmtypes_jar)
  list(APPEND spy_depends birotor_lcmtypes_jar)
endif()
birotor_man_page(birotor-lcm-spy ${PROJECT_SOURCE_DIR}/tools/lcm-spy.sh ${spy_depends})
add_custom_target(birotor_package_docs ALL DEPENDS ${BIROTOR_MAN_PAGES} ${doc_dir}/changelog.gz)

install(FILES ${BIROTOR_MAN_PAGES} DESTINATION share/man/man1)
install(FILES ${PROJECT_SOURCE_DIR}/deploy/copyright ${doc_dir}/changelog.gz DESTINATION share/doc/birotor)
