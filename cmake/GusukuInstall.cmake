# `cmake --install BUILD --prefix P` installs what an app links, as the CMake package "gusuku" (find_package):
#   component runtime  gusuku_formats, gusuku_maths, gusuku_gpu, gusuku_runtime and gusuku_pack_loader (static), their headers
#                      (gusuku/formats/, gusuku/maths/, gusuku/gpu/, gusuku/runtime/: the C++ API runtime.h and the C API gusuku.h
#                      among them; of gusuku/loader/ the pack reader's runtime_pack.h and the C gusuku_loader.h,
#                      whose gusuku_bakeset_load_pack it defines), the licence and the package files;
#                      find_package(gusuku) gives gusuku::runtime and gusuku::pack_loader, which need Vulkan and
#                      glm only: a phone app reads the bake set's runtime pack without the tools' I/O stack;
#                      gusuku_weather (gusuku/weather/: the METAR and Open-Meteo readers, C++ and C) and
#                      gusuku_json (their private JSON reader: the archive only, no header) likewise, and
#                      gusuku_c_common (the C API's error reporting that they all share: the archive only)
#   component loader   gusuku_loader and gusuku_assets (static): find_package(gusuku COMPONENTS loader) gives
#                      gusuku::loader, with their headers (gusuku/assets/, gusuku/loader/); it needs the tools'
#                      I/O stack (OpenImageIO, OpenColorIO, tinygltf, nlohmann-json, GeographicLib: Debian
#                      packages, found again by the package config)
# A runtime-only build (GUSUKU_RUNTIME_ONLY) installs the runtime component alone.
# Relocatable: every exported link names an imported target that the package config finds again (Vulkan, glm,
# the loader's I/O stack), never a path on the build machine; install_and_consume checks the installed files.
# Not installed: the baker, the tools, the embedded SPIR-V and the shader interface headers (shaders/include),
# which only the runtime's private sources include.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
set(GUSUKU_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/gusuku)

set_target_properties(gusuku_formats PROPERTIES EXPORT_NAME formats)
set_target_properties(gusuku_maths PROPERTIES EXPORT_NAME maths)
set_target_properties(gusuku_gpu PROPERTIES EXPORT_NAME gpu)
set_target_properties(gusuku_runtime PROPERTIES EXPORT_NAME runtime)
# The installed headers are C++17 (Android NDK and Unity native-plugin code mostly is; the sources may be C++20):
# a consumer gets at least C++17 from the targets, and tests/consumer compiles every header as C++17.
foreach(runtime_library gusuku_formats gusuku_maths gusuku_gpu gusuku_runtime)
  target_compile_features(${runtime_library} INTERFACE cxx_std_17)
endforeach()

# gusuku_pack_loader (the runtime pack's reader, standard library only) is the phone's loader, so it ships with the
# runtime; gusuku_loader (the EXR bake set, the I/O stack) links it.
set_target_properties(gusuku_pack_loader PROPERTIES EXPORT_NAME pack_loader)
target_compile_features(gusuku_pack_loader INTERFACE cxx_std_17)
set_target_properties(gusuku_weather PROPERTIES EXPORT_NAME weather)
set_target_properties(gusuku_json PROPERTIES EXPORT_NAME json)
# gusuku_c_common: the C API's error reporting and bake set handle, which the runtime, the loaders and the weather
# readers share (the archive only, no header), so gusuku_last_error_message is defined once in an app's link.
set_target_properties(gusuku_c_common PROPERTIES EXPORT_NAME c_common)
target_compile_features(gusuku_weather INTERFACE cxx_std_17)
install(TARGETS gusuku_formats gusuku_maths gusuku_gpu gusuku_runtime gusuku_pack_loader gusuku_weather gusuku_json
                gusuku_c_common
        EXPORT gusukuRuntimeTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# Headers by library: engine/include/gusuku/<library>/ holds the public headers of gusuku_<library>, and each
# component installs the folders of exactly the libraries it installs.
foreach(library formats maths gpu runtime weather)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/gusuku/${library} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/gusuku
          COMPONENT runtime FILES_MATCHING PATTERN "*.h")
endforeach()
set(GUSUKU_PACK_LOADER_HEADERS runtime_pack.h gusuku_loader.h)
foreach(header ${GUSUKU_PACK_LOADER_HEADERS})
  install(FILES ${PROJECT_SOURCE_DIR}/engine/include/gusuku/loader/${header}
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/gusuku/loader COMPONENT runtime)
endforeach()
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/gusuku COMPONENT runtime)
install(EXPORT gusukuRuntimeTargets NAMESPACE gusuku:: DESTINATION ${GUSUKU_INSTALL_CMAKEDIR} COMPONENT runtime)

if(NOT GUSUKU_RUNTIME_ONLY)
  set_target_properties(gusuku_assets PROPERTIES EXPORT_NAME assets)
  set_target_properties(gusuku_loader PROPERTIES EXPORT_NAME loader)
  install(TARGETS gusuku_assets gusuku_loader EXPORT gusukuLoaderTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT loader
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  foreach(library assets loader)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/gusuku/${library}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/gusuku COMPONENT loader FILES_MATCHING PATTERN "*.h"
            PATTERN runtime_pack.h EXCLUDE PATTERN gusuku_loader.h EXCLUDE)  # the runtime component's
  endforeach()
  install(EXPORT gusukuLoaderTargets NAMESPACE gusuku:: DESTINATION ${GUSUKU_INSTALL_CMAKEDIR} COMPONENT loader)
  # The package config recreates GeographicLib::GeographicLib with it (the exported link names that target).
  install(FILES ${PROJECT_SOURCE_DIR}/cmake/GusukuGeographicLibTarget.cmake DESTINATION ${GUSUKU_INSTALL_CMAKEDIR}
          COMPONENT loader)
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/gusukuConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/gusukuConfig.cmake INSTALL_DESTINATION ${GUSUKU_INSTALL_CMAKEDIR})
# 0.x: a new minor version may change the API, so only the same major.minor satisfies a request.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/gusukuConfigVersion.cmake VERSION ${PROJECT_VERSION}
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/gusukuConfig.cmake ${PROJECT_BINARY_DIR}/gusukuConfigVersion.cmake
        DESTINATION ${GUSUKU_INSTALL_CMAKEDIR} COMPONENT runtime)
