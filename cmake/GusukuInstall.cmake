# `cmake --install BUILD --prefix P` installs what an app links, as the CMake package "gusuku" (find_package):
#   component runtime  gusuku_formats, gusuku_maths, gusuku_gpu, gusuku_runtime and gusuku_pack_loader (static), the
#                      headers an app includes (the C++ API runtime.h, the C API gusuku.h, the pack reader's
#                      gusuku/pack_loader/, the weather readers') and what those include (the list below), the
#                      licence and the package files;
#                      find_package(gusuku) gives gusuku::runtime and gusuku::pack_loader, which need Vulkan and
#                      glm only: a phone app reads the bake set's runtime pack without the tools' I/O stack;
#                      gusuku_weather (gusuku/weather/: the METAR and Open-Meteo readers, C++ and C) and
#                      gusuku_json (their private JSON reader: the archive only, no header) likewise, and
#                      gusuku_c_common (the C API's error reporting that they all share: the archive only)
#   component loader   gusuku_loader and gusuku_assets (static): find_package(gusuku COMPONENTS loader) gives
#                      gusuku::loader, with their headers (gusuku/assets/, gusuku/loader/ and what those include
#                      beyond the runtime component's); it needs the tools'
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
# Headers: what an app includes and what those include, nothing else, so an app's public surface is its API and
# not the libraries' internals. The runtime component's entry headers, each for:
#   gusuku/runtime/gusuku.h                the C API
#   gusuku/runtime/runtime.h               the C++ API
#   gusuku/runtime/runtime_version.h       the C++ version query (runtimeVersion)
#   gusuku/runtime/runtime_sun_evidence.h  the sun read from the frame (latestSunEvidence)
#   gusuku/pack_loader/gusuku_pack_loader.h, runtime_pack.h    the runtime pack's reader, C and C++
#   gusuku/weather/gusuku_weather.h, weather_service.h         the weather services' readers, C and C++
# and, because those include them (gusuku_header_closure walks the "gusuku/..." include lines, so an include added
# there is installed at the next build and the list below is only an account of today's):
#   gusuku/formats/bakeset_data.h, bakeset_manifest.h, ground_grid.h    runtime.h's BakeSetData, what open() takes
#   gusuku/maths/colour_match.h, colour.h, const_span.h                 runtime.h's colour match settings
#   gusuku/gpu/gpu_device.h                                             runtime.h's app-owned device
#   gusuku/maths/sun_visibility.h                                       weather_service.h's SkyRegime, the sun's
#                                                                       state filter an app runs per frame
# Each header sits in engine/include/gusuku/<library>/, the folder of the library that provides it.
# install_and_consume checks that every installed header is reached from an entry header, and compiles each alone.
include(${CMAKE_CURRENT_LIST_DIR}/GusukuHeaderClosure.cmake)
set(GUSUKU_INCLUDE_ROOT ${PROJECT_SOURCE_DIR}/engine/include)
gusuku_header_closure(GUSUKU_RUNTIME_HEADERS ${GUSUKU_INCLUDE_ROOT}
  gusuku/runtime/gusuku.h gusuku/runtime/runtime.h gusuku/runtime/runtime_version.h
  gusuku/runtime/runtime_sun_evidence.h
  gusuku/pack_loader/gusuku_pack_loader.h gusuku/pack_loader/runtime_pack.h
  gusuku/weather/gusuku_weather.h gusuku/weather/weather_service.h)
foreach(header ${GUSUKU_RUNTIME_HEADERS})
  get_filename_component(header_folder ${header} DIRECTORY)
  install(FILES ${GUSUKU_INCLUDE_ROOT}/${header} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${header_folder}
          COMPONENT runtime)
endforeach()
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/gusuku COMPONENT runtime)
# The GPU-resident frame loop in a window, the smallest version of gusuku-view's (docs/view.md): source to copy,
# compiled against the installed package by install_and_consume where GLFW is.
install(FILES ${PROJECT_SOURCE_DIR}/tests/consumer/present_loop.cpp DESTINATION ${CMAKE_INSTALL_DATADIR}/gusuku/examples
        COMPONENT runtime)
install(EXPORT gusukuRuntimeTargets NAMESPACE gusuku:: DESTINATION ${GUSUKU_INSTALL_CMAKEDIR} COMPONENT runtime)

if(NOT GUSUKU_RUNTIME_ONLY)
  set_target_properties(gusuku_assets PROPERTIES EXPORT_NAME assets)
  set_target_properties(gusuku_loader PROPERTIES EXPORT_NAME loader)
  install(TARGETS gusuku_assets gusuku_loader EXPORT gusukuLoaderTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT loader
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  # The loader component's entry headers: gusuku/loader/ (the C gusuku_bakeset_load) and gusuku/assets/ (the C++
  # loadBakeSet and the tools' readers it is built from), and what they include beyond the runtime component's.
  file(GLOB loader_entry_headers RELATIVE ${GUSUKU_INCLUDE_ROOT}
       ${GUSUKU_INCLUDE_ROOT}/gusuku/loader/*.h ${GUSUKU_INCLUDE_ROOT}/gusuku/assets/*.h)
  gusuku_header_closure(GUSUKU_LOADER_HEADERS ${GUSUKU_INCLUDE_ROOT} ${loader_entry_headers})
  list(REMOVE_ITEM GUSUKU_LOADER_HEADERS ${GUSUKU_RUNTIME_HEADERS})
  foreach(header ${GUSUKU_LOADER_HEADERS})
    get_filename_component(header_folder ${header} DIRECTORY)
    install(FILES ${GUSUKU_INCLUDE_ROOT}/${header} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${header_folder}
            COMPONENT loader)
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
