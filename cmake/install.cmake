# cmake --install: the layer libraries, their public headers, <cellforge/cellforge.h>
# and a package config, so that another project can write
#   find_package(cellforge REQUIRED)
#   target_link_libraries(app PRIVATE cellforge::cellforge)
# compare/ (a test and benchmark layer) is not installed.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(CELLFORGE_INSTALLED_TARGETS cellforge)
foreach(name ${CELLFORGE_LAYERS})
  list(APPEND CELLFORGE_INSTALLED_TARGETS cellforge_${name})
  if(IS_DIRECTORY ${CMAKE_SOURCE_DIR}/include/cellforge/${name})
    install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/cellforge/${name}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/cellforge)
  endif()
endforeach()
install(TARGETS ${CELLFORGE_INSTALLED_TARGETS} EXPORT cellforgeTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(FILES ${CMAKE_SOURCE_DIR}/include/cellforge/ids.h
              ${CMAKE_SOURCE_DIR}/include/cellforge/result.h
              ${CMAKE_BINARY_DIR}/layers/all/public/cellforge/cellforge.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/cellforge)
install(TARGETS cellforge_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

set(CELLFORGE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/cellforge)
install(EXPORT cellforgeTargets NAMESPACE cellforge:: DESTINATION ${CELLFORGE_CMAKE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/cellforgeConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/cellforgeConfig.cmake
                              INSTALL_DESTINATION ${CELLFORGE_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cellforgeConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cellforgeConfig.cmake
              ${CMAKE_BINARY_DIR}/cellforgeConfigVersion.cmake
        DESTINATION ${CELLFORGE_CMAKE_DIR})
