# Finds the tools' I/O stack from Debian 12's packages, with the two package-config faults worked around once
# for every build that needs them (the main build, tests/fuzz):
#   - Debian 12's OpenImageIO target lists /usr/include/opencv4 as an include directory although OpenCV is only an
#     optional plugin dependency: include directories that do not exist are dropped rather than pull in OpenCV;
#   - Debian 12's OpenColorIO CMake config sits in /usr/share/cmake and computes a wrong prefix ("/include"), so
#     OpenColorIO is found through pkg-config instead, as OpenColorIO::OpenColorIO.
# Defines glm::glm, TinyGLTF::TinyGLTF, OpenImageIO::OpenImageIO(_Util), OpenColorIO::OpenColorIO,
# nlohmann_json::nlohmann_json, GeographicLib::GeographicLib (cmake/GusukuGeographicLibTarget.cmake: a target, so
# that exported links hold no absolute path) and GeographicLib_INCLUDE_DIRS / GeographicLib_LIBRARIES.
find_package(glm REQUIRED)
find_package(TinyGLTF REQUIRED)
find_package(OpenImageIO REQUIRED)
foreach(oiio_target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  get_target_property(oiio_includes ${oiio_target} INTERFACE_INCLUDE_DIRECTORIES)
  if(oiio_includes)
    set(existing_includes)
    foreach(dir ${oiio_includes})
      if(EXISTS ${dir})
        list(APPEND existing_includes ${dir})
      endif()
    endforeach()
    set_target_properties(${oiio_target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${existing_includes}")
  endif()
endforeach()
find_package(PkgConfig REQUIRED)
pkg_check_modules(OpenColorIO REQUIRED IMPORTED_TARGET OpenColorIO)
if(NOT TARGET OpenColorIO::OpenColorIO)
  add_library(OpenColorIO::OpenColorIO ALIAS PkgConfig::OpenColorIO)
endif()
find_package(nlohmann_json 3 REQUIRED)
list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
find_package(GeographicLib REQUIRED)
include(${CMAKE_CURRENT_LIST_DIR}/GusukuGeographicLibTarget.cmake)
if(NOT TARGET GeographicLib::GeographicLib)
  message(FATAL_ERROR "GeographicLib: libGeographicLib or GeographicLib/Config.h not found on the search path")
endif()
