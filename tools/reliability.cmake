# Reliability tools (issue 7): the soak monitor used by tools/soak.sh and the
# soak test in tests/reliability/.
add_executable(birotor-soak-monitor ${CMAKE_CURRENT_LIST_DIR}/birotor_soak_monitor_main.cc)
target_link_libraries(birotor-soak-monitor PRIVATE birotor_transport)
install(TARGETS birotor-soak-monitor RUNTIME DESTINATION bin)
