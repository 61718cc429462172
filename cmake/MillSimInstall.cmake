# Installation and the CMake package: integrators write
#   find_package(MillSim REQUIRED)
#   target_link_libraries(myapp PRIVATE MillSim::millsim)
include(CMakePackageConfigHelpers)

# MillSim::millsim brings MillSim::scene (libmillsim_scene: the node graph, no
# OpenVDB), which a plugin of nodes alone may link instead. libmillsim_medical
# (VTK, GDCM) is exported too: integrators that mesh volumes link
# MillSim::medical (IsoSurface.h); libmillsim opens it next to itself.
install(TARGETS millsim_scene millsim millsim_medical EXPORT MillSimTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS millsim-app RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The process that reads a .vdb first (millsim/volume/VdbProbeMain.cpp); readVdb
# finds it from libmillsim by the relative path of libexec/millsim.
install(TARGETS millsim-vdb-probe RUNTIME DESTINATION ${CMAKE_INSTALL_LIBEXECDIR}/millsim)
# The command's verbs, next to libmillsim_scene where the command opens them (apps/CliModule.h).
install(TARGETS millsim_cli LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
# libmillsim_graphics sits next to libmillsim, where loadGraphicsModule() looks for it.
install(TARGETS millsim_graphics LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS millsim_audio LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
# libmillsim_window too: an installed `millsim run` opens its window with it (loadWindowModule).
install(TARGETS millsim_window LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
# The public headers: every library header but the internals listed in
# cmake/private-headers.txt (scripts/include-graph checks that no public header
# includes one, and that none reaches Eigen or VTK).
file(STRINGS ${CMAKE_SOURCE_DIR}/cmake/private-headers.txt _private REGEX "^millsim/")
set(_exclude "")
foreach(_h IN LISTS _private)
  string(REGEX REPLACE "^millsim/" "" _h ${_h})
  string(REPLACE "." "\\." _h ${_h})
  list(APPEND _exclude REGEX "/${_h}$" EXCLUDE)
endforeach()
install(DIRECTORY ${CMAKE_SOURCE_DIR}/millsim/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/millsim
        FILES_MATCHING PATTERN "*.h" ${_exclude})
install(EXPORT MillSimTargets NAMESPACE MillSim:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/MillSim)

configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/MillSimConfig.cmake.in
  ${CMAKE_BINARY_DIR}/MillSimConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/MillSim)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/MillSimConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/MillSimConfig.cmake ${CMAKE_BINARY_DIR}/MillSimConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/MillSim)
