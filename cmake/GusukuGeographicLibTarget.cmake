# Defines the imported target GeographicLib::GeographicLib (library and include directory) if it is not defined
# yet and GeographicLib is found; leaves it undefined otherwise, for the includer to report.
# Why a target of our own: GeographicLib ships a find module (Debian 12: /usr/share/cmake/geographiclib) that gives
# only an absolute library path, and a path linked by gusuku_assets would be written into the exported loader
# target as it is on the build machine (/usr/lib/x86_64-linux-gnu/...), so the package would not move to another
# prefix or architecture. The main build (cmake/IoStackPackages.cmake) and the installed package config
# (cmake/gusukuConfig.cmake.in) both include this file, so the exported link names the target and each
# consumer finds the library on its own search path.
if(NOT TARGET GeographicLib::GeographicLib)
  find_library(GUSUKU_GEOGRAPHICLIB_LIBRARY NAMES GeographicLib)
  find_path(GUSUKU_GEOGRAPHICLIB_INCLUDE_DIR GeographicLib/Config.h)
  mark_as_advanced(GUSUKU_GEOGRAPHICLIB_LIBRARY GUSUKU_GEOGRAPHICLIB_INCLUDE_DIR)
  if(GUSUKU_GEOGRAPHICLIB_LIBRARY AND GUSUKU_GEOGRAPHICLIB_INCLUDE_DIR)
    add_library(GeographicLib::GeographicLib UNKNOWN IMPORTED)
    set_target_properties(GeographicLib::GeographicLib PROPERTIES
                          IMPORTED_LOCATION ${GUSUKU_GEOGRAPHICLIB_LIBRARY}
                          INTERFACE_INCLUDE_DIRECTORIES ${GUSUKU_GEOGRAPHICLIB_INCLUDE_DIR})
  endif()
endif()
