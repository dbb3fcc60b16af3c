# Estimator daemon (issue 4): the LCM glue library shared with birotor-replay,
# and the birotor-estimator program. Included from services/CMakeLists.txt.
add_library(birotor_estimator_service STATIC
  ${CMAKE_CURRENT_LIST_DIR}/estimator_service.cc
  ${CMAKE_CURRENT_LIST_DIR}/gauge_state_file.cc
  ${CMAKE_CURRENT_LIST_DIR}/input_rejection_log.cc
  ${CMAKE_CURRENT_LIST_DIR}/status_message.cc)
target_include_directories(birotor_estimator_service PUBLIC ${PROJECT_SOURCE_DIR})
target_link_libraries(birotor_estimator_service PUBLIC
  birotor_estimator birotor_numerics birotor_params birotor_sinks birotor_transport)
target_link_libraries(birotor_estimator_service PRIVATE birotor_warnings)

add_executable(birotor-estimator ${CMAKE_CURRENT_LIST_DIR}/birotor_estimator_main.cc)
target_link_libraries(birotor-estimator PRIVATE birotor_estimator_service birotor_warnings)
install(TARGETS birotor-estimator RUNTIME DESTINATION bin)
