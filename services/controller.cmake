# Flight-controller daemon (issue 12): the LCM glue library and the
# birotor-controller program. Included from services/CMakeLists.txt.
add_library(birotor_controller_service STATIC ${CMAKE_CURRENT_LIST_DIR}/controller_service.cc)
target_include_directories(birotor_controller_service PUBLIC ${PROJECT_SOURCE_DIR})
target_link_libraries(birotor_controller_service PUBLIC
  birotor_controller birotor_numerics birotor_params birotor_sinks birotor_transport)
target_link_libraries(birotor_controller_service PRIVATE birotor_warnings)

add_executable(birotor-controller ${CMAKE_CURRENT_LIST_DIR}/birotor_controller_main.cc)
target_link_libraries(birotor-controller PRIVATE birotor_controller_service birotor_warnings)
install(TARGETS birotor-controller RUNTIME DESTINATION bin)
