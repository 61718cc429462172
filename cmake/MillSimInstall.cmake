# Installation and the CMake package: integrators write
#   find_package(MillSim REQUIRED)
#   target_link_libraries(myapp PRIVATE MillSim::millsim)
include(CMakePackageConfigHelpers)

install(TARGETS millsim EXPORT MillSimTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS millsim-app RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# libmillsim_graphics sits next to libmillsim, where loadGraphicsModule() looks for it.
install(TARGETS millsim_graphics LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/millsim/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/millsim
        FILES_MATCHING PATTERN "*.h")
install(EXPORT MillSimTargets NAMESPACE MillSim:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/MillSim)

configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/MillSimConfig.cmake.in
  ${CMAKE_BINARY_DIR}/MillSimConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/MillSim)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/MillSimConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/MillSimConfig.cmake ${CMAKE_BINARY_DIR}/MillSimConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/MillSim)
