# birotor-monitor (issue 6): live terminal view of a running simulator and
# estimator, and birotor-eval's error figures over what it received. Included
# from tools/CMakeLists.txt after the birotor_replay library is defined.
add_library(birotor_monitor STATIC
  ${CMAKE_CURRENT_LIST_DIR}/birotor_monitor_collector.cc
  ${CMAKE_CURRENT_LIST_DIR}/birotor_monitor_view.cc)
target_include_directories(birotor_monitor PUBLIC ${PROJECT_SOURCE_DIR})
target_link_libraries(birotor_monitor PUBLIC birotor_replay birotor_plotting birotor_transport)

add_executable(birotor-monitor ${CMAKE_CURRENT_LIST_DIR}/birotor_monitor_main.cc)
target_link_libraries(birotor-monitor PRIVATE birotor_monitor)
install(TARGETS birotor-monitor RUNTIME DESTINATION bin)
