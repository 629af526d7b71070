# cmake --install BUILD --prefix P: the tools (P/bin), the library's headers (P/include/mcws) and
# static libraries (P/lib), and the CMake package (P/lib/cmake/mcws) with exported targets
# mcws::<module>, so that another project does find_package(mcws CONFIG REQUIRED).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# Target name -> exported name (mcws_io -> mcws::io; the reach library is mcws::reach).
set(mcws_exported
  mcws_core core  mcws_points points  mcws_kinematics kinematics  mcws_search search
  mcws_io io  mcws_sampling sampling  mcws_filters filters  mcws_workspace workspace
  mcws_collision collision  mcws_trajectory trajectory  mcws_reachability reach
  mcws_planning_graph planning_graph  mcws_planning planning
  mcws_behavior_model behavior_model  mcws_behavior_sim behavior_sim
  mcws_behavior_faults behavior_faults  mcws_behavior_exec behavior_exec
  mcws_behavior_report behavior_report  mcws_behavior behavior
  mcws_distributed distributed  mcws_report report  mcws_study_lib study
  mcws_pcl pcl  mcws_warnings warnings)
set(mcws_install_targets "")
list(LENGTH mcws_exported count)
math(EXPR last "${count} - 1")
foreach(i RANGE 0 ${last} 2)
  math(EXPR j "${i} + 1")
  list(GET mcws_exported ${i} target)
  list(GET mcws_exported ${j} name)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  list(APPEND mcws_install_targets ${target})
endforeach()

install(TARGETS ${mcws_install_targets} EXPORT mcwsTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# Public headers only: detail/ folders are a module's own.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/mcws ${PROJECT_SOURCE_DIR}/filters/include/mcws
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h" PATTERN "*.hpp" PATTERN "detail" EXCLUDE)
install(EXPORT mcwsTargets NAMESPACE mcws:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mcws)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/mcwsConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/mcwsConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mcws)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/mcwsConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/mcwsConfig.cmake ${PROJECT_BINARY_DIR}/mcwsConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mcws)

# The stage tools.
foreach(dir apps)
  get_property(targets DIRECTORY ${PROJECT_SOURCE_DIR}/${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target ${targets})
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      install(TARGETS ${target} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    endif()
  endforeach()
endforeach()
