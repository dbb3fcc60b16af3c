# birotor-analyze: model analysis command (foundation issue).
add_executable(birotor-analyze ${CMAKE_CURRENT_LIST_DIR}/birotor_analyze_main.cc)
target_link_libraries(birotor-analyze PRIVATE birotor_estimator birotor_params birotor_transport)
install(TARGETS birotor-analyze RUNTIME DESTINATION bin)
