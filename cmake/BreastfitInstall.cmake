# Installation: `cmake --install <build> --prefix P` gives
#   P/include/breastfit/<layer>/*.h          public headers (detail/ headers are private to their layer)
#   P/lib/libbreastfit_<layer>.a             the layer libraries
#   P/lib/cmake/breastfit/                   breastfitConfig.cmake, breastfitConfigVersion.cmake,
#                                            breastfitTargets*.cmake, stb.cmake,
#                                            libdeflate.cmake, nettle.cmake, import_library.cmake
#   P/bin/breastfit, P/bin/breastfit-serve   the CLI and the workstation it runs (apps/cli/CMakeLists.txt)
#   P/share/breastfit/default_torso.glb      the shipped template
# so that a consumer's find_package(breastfit) gives breastfit::breastfit and breastfit::<layer>.
include(CMakePackageConfigHelpers)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/breastfit DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h" PATTERN "detail" EXCLUDE)
install(FILES ${PROJECT_SOURCE_DIR}/assets/templates/default_torso.glb DESTINATION ${CMAKE_INSTALL_DATADIR}/breastfit)

set(_breastfit_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/breastfit)
install(EXPORT breastfitTargets NAMESPACE breastfit:: DESTINATION ${_breastfit_cmake_dir})
set(BREASTFIT_TEMPLATE_INSTALL_FILE ${CMAKE_INSTALL_DATADIR}/breastfit/default_torso.glb)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/breastfitConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/breastfitConfig.cmake
                              INSTALL_DESTINATION ${_breastfit_cmake_dir}
                              PATH_VARS BREASTFIT_TEMPLATE_INSTALL_FILE)
# 0.x: minor versions may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/breastfitConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/breastfitConfig.cmake ${PROJECT_BINARY_DIR}/breastfitConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/deps/stb.cmake ${PROJECT_SOURCE_DIR}/cmake/deps/libdeflate.cmake
              ${PROJECT_SOURCE_DIR}/cmake/deps/nettle.cmake ${PROJECT_SOURCE_DIR}/cmake/deps/import_library.cmake
        DESTINATION ${_breastfit_cmake_dir})
