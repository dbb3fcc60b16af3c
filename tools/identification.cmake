# birotor-identify: identification of the vehicle parameters from LCM logs.
# Included from tools/CMakeLists.txt; paths are relative to this file.
add_library(birotor_identification_logs STATIC ${CMAKE_CURRENT_LIST_DIR}/identification_log_loader.cc)
target_include_directories(birotor_identification_logs PUBLIC ${PROJECT_SOURCE_DIR})
target_link_libraries(birotor_identification_logs PUBLIC birotor_identification birotor_transport)

add_executable(birotor-identify ${CMAKE_CURRENT_LIST_DIR}/birotor_identify_main.cc
               ${CMAKE_CURRENT_LIST_DIR}/identification_plot.cc)
target_link_libraries(birotor-identify PRIVATE birotor_identification_logs birotor_identification
                      birotor_transport birotor_params birotor_plotting)
install(TARGETS birotor-identify RUNTIME DESTINATION bin)
