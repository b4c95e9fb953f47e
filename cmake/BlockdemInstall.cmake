# Install rules and the package config, so that find_package(blockdem) works after `cmake --install`.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS blockdem EXPORT blockdemTargets)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
set(blockdem_config_dir "${CMAKE_INSTALL_DATADIR}/cmake/blockdem")
install(EXPORT blockdemTargets NAMESPACE blockdem:: DESTINATION "${blockdem_config_dir}")
configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/blockdemConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/blockdemConfig.cmake" INSTALL_DESTINATION "${blockdem_config_dir}")
# Header-only: the version file must not pin the architecture.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/blockdemConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion ARCH_INDEPENDENT)
install(FILES "${PROJECT_BINARY_DIR}/blockdemConfig.cmake" "${PROJECT_BINARY_DIR}/blockdemConfigVersion.cmake"
  DESTINATION "${blockdem_config_dir}")
