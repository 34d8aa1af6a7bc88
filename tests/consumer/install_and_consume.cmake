# cmake -DBUILD_DIR=... -DCONSUMER_SOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=... [-DC_COMPILER=... -DCXX_COMPILER=...]
#       [-DWITH_LOADER=OFF] [-DRUN_CONSUMERS=OFF] [-DTOOLCHAIN_FILE=...] -P install_and_consume.cmake
# Installs the build into WORK_DIR/staging and moves it to WORK_DIR/prefix (so the package must be relocatable;
# its CMake files are also checked for absolute paths), installs the runtime component alone into another prefix
# (to check the split), configures and builds the consumer against WORK_DIR/prefix alone (CMAKE_PREFIX_PATH), and
# runs its programs. Any step failing fails the test.
#   WITH_LOADER     ON (default): the build has the loader component; OFF: a runtime-only build (GUSUKU_RUNTIME_ONLY)
#   RUN_CONSUMERS   ON (default); OFF when the consumers are cross-compiled (scripts/cross-build-aarch64.sh)
#   TOOLCHAIN_FILE  the consumer's CMAKE_TOOLCHAIN_FILE, for a cross build
foreach(variable BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR GENERATOR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "install_and_consume.cmake: ${variable} is not set")
  endif()
endforeach()
if(NOT DEFINED WITH_LOADER)
  set(WITH_LOADER ON)
endif()
if(NOT DEFINED RUN_CONSUMERS)
  set(RUN_CONSUMERS ON)
endif()
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run_step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  message(STATUS "${name}:\n${output}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${name} failed (${result})")
  endif()
endfunction()

run_step("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/staging)
file(RENAME ${WORK_DIR}/staging ${prefix})  # the package is used where it was not installed
set(expected_files include/gusuku/runtime/gusuku.h include/gusuku/runtime/runtime.h
                   include/gusuku/pack_loader/runtime_pack.h include/gusuku/pack_loader/gusuku_pack_loader.h
                   lib/libgusuku_pack_loader.a
                   include/gusuku/weather/gusuku_weather.h include/gusuku/weather/weather_service.h
                   lib/libgusuku_weather.a lib/libgusuku_json.a lib/libgusuku_c_common.a
                   lib/cmake/gusuku/gusukuConfig.cmake lib/cmake/gusuku/gusukuConfigVersion.cmake
                   share/gusuku/examples/present_loop.cpp)
if(WITH_LOADER)
  list(APPEND expected_files include/gusuku/loader/gusuku_loader.h)
else()
  foreach(absent lib/libgusuku_assets.a lib/libgusuku_loader.a lib/cmake/gusuku/gusukuLoaderTargets.cmake
          include/gusuku/assets include/gusuku/loader include/gusuku/tools)
    if(EXISTS ${prefix}/${absent})
      message(FATAL_ERROR "install: ${absent} is in the prefix of a runtime-only build")
    endif()
  endforeach()
endif()
foreach(expected ${expected_files})
  if(NOT EXISTS ${prefix}/${expected})
    message(FATAL_ERROR "install: ${expected} is missing from the prefix")
  endif()
endforeach()
file(GLOB interface_headers ${prefix}/include/*_interface.h ${prefix}/include/gusuku/*_interface.h)
if(interface_headers)
  message(FATAL_ERROR "install: shader interface headers are private, yet installed: ${interface_headers}")
endif()

# Relocatable: no absolute path in the package's CMake files (a library path of the build machine, such as
# /usr/lib/x86_64-linux-gnu/libGeographicLib.so, would break another prefix, machine or architecture). A path
# is a '/' after a quote, ';', space or '(' and followed by a name; comment lines are skipped.
file(GLOB package_files ${prefix}/lib/cmake/gusuku/*.cmake)
set(absolute_paths)
foreach(package_file ${package_files})
  # Read whole (file(STRINGS) would split the lines at the ';' of link lists), comment lines removed.
  file(READ ${package_file} content)
  string(REGEX REPLACE "(^|\n)[ \t]*#[^\n]*" "\\1" content "${content}")
  string(REGEX MATCHALL "[\"; (]/[^\"; )\n]+" found "${content}")
  get_filename_component(file_name ${package_file} NAME)
  foreach(path ${found})  # a match after ';' comes as its own list item, the ';' gone
    string(REGEX REPLACE "^[^/]" "" path "${path}")
    list(APPEND absolute_paths "${file_name}: ${path}")
  endforeach()
endforeach()
if(absolute_paths)
  list(JOIN absolute_paths "\n  " absolute_paths)
  message(FATAL_ERROR "install: the package's CMake files hold absolute paths (not relocatable):\n  ${absolute_paths}")
endif()
list(LENGTH package_files package_file_count)
message(STATUS "package files: ${package_file_count}, no absolute path")

# The runtime component alone: the lean libraries and the package, nothing of the loader's I/O stack.
run_step("install the runtime component" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/runtime_only
         --component runtime)
foreach(absent lib/libgusuku_assets.a lib/libgusuku_loader.a lib/cmake/gusuku/gusukuLoaderTargets.cmake)
  if(EXISTS ${WORK_DIR}/runtime_only/${absent})
    message(FATAL_ERROR "install --component runtime: ${absent} belongs to the loader component")
  endif()
endforeach()
foreach(library runtime pack_loader weather json)
  if(NOT EXISTS ${WORK_DIR}/runtime_only/lib/libgusuku_${library}.a)
    message(FATAL_ERROR "install --component runtime: lib/libgusuku_${library}.a is missing")
  endif()
endforeach()
# Headers by library: the runtime component carries the headers of the libraries it installs and no others (the
# pack reader's in gusuku/pack_loader/; gusuku/loader/, the EXR loader's, is the loader component's alone).
foreach(folder formats maths gpu runtime weather pack_loader)
  if(NOT IS_DIRECTORY ${WORK_DIR}/runtime_only/include/gusuku/${folder})
    message(FATAL_ERROR "install --component runtime: include/gusuku/${folder}/ is missing")
  endif()
endforeach()
file(GLOB runtime_only_entries RELATIVE ${WORK_DIR}/runtime_only/include/gusuku
     ${WORK_DIR}/runtime_only/include/gusuku/*)
list(REMOVE_ITEM runtime_only_entries formats maths gpu runtime weather pack_loader)
if(runtime_only_entries)
  message(FATAL_ERROR "install --component runtime: include/gusuku/ also holds ${runtime_only_entries}, "
                      "headers of libraries the component does not install")
endif()
# Only what an app includes: each header of the runtime component is an entry header (what an app includes:
# the C and C++ APIs, the pack reader's, the weather readers', the sun evidence reading) or named by an include
# line of another installed header; cmake/GusukuInstall.cmake says why each is there.
set(runtime_entry_headers gusuku/runtime/gusuku.h gusuku/runtime/runtime.h gusuku/runtime/runtime_version.h
    gusuku/runtime/runtime_sun_evidence.h
    gusuku/pack_loader/gusuku_pack_loader.h gusuku/pack_loader/runtime_pack.h gusuku/weather/gusuku_weather.h
    gusuku/weather/weather_service.h)
file(GLOB_RECURSE runtime_only_headers RELATIVE ${WORK_DIR}/runtime_only/include
     ${WORK_DIR}/runtime_only/include/gusuku/*.h)
set(runtime_included_headers)
foreach(header ${runtime_only_headers})
  file(STRINGS ${WORK_DIR}/runtime_only/include/${header} include_lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]gusuku/")
  foreach(line ${include_lines})
    string(REGEX MATCH "gusuku/[^>\"]+" included "${line}")
    list(APPEND runtime_included_headers ${included})
  endforeach()
endforeach()
set(runtime_unreached_headers ${runtime_only_headers})
list(REMOVE_ITEM runtime_unreached_headers ${runtime_entry_headers} ${runtime_included_headers})
list(LENGTH runtime_only_headers runtime_only_header_count)
message(STATUS "install --component runtime: ${runtime_only_header_count} headers")
if(runtime_unreached_headers)
  message(FATAL_ERROR "install --component runtime: ${runtime_unreached_headers} installed, yet no app includes "
                      "them (neither an entry header nor included by an installed header)")
endif()
if(NOT EXISTS ${WORK_DIR}/runtime_only/share/doc/gusuku/LICENSE)
  message(FATAL_ERROR "install --component runtime: share/doc/gusuku/LICENSE is missing")
endif()

# Every installed header, each compiled on its own (one translation unit each) by the consumer below.
file(GLOB_RECURSE installed_headers RELATIVE ${prefix}/include ${prefix}/include/gusuku/*.h)
list(LENGTH installed_headers installed_header_count)
message(STATUS "installed headers: ${installed_header_count}")
# Passed to the consumer joined by '|': run_step's ARGN would split a ';' list into separate arguments.
list(JOIN installed_headers "|" installed_headers_joined)

set(compilers)
if(C_COMPILER)
  list(APPEND compilers -DCMAKE_C_COMPILER=${C_COMPILER})
endif()
if(CXX_COMPILER)
  list(APPEND compilers -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
if(TOOLCHAIN_FILE)
  list(APPEND compilers -DCMAKE_TOOLCHAIN_FILE=${TOOLCHAIN_FILE})
endif()
run_step("configure the consumer" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
         -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix} ${compilers} -DGUSUKU_CONSUMER_LOADER=${WITH_LOADER}
         "-DGUSUKU_INSTALLED_HEADERS=${installed_headers_joined}")
run_step("build the consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
if(RUN_CONSUMERS)
  run_step("run consumer_runtime" ${WORK_DIR}/build/consumer_runtime)
  run_step("run consumer_runtime_cxx17" ${WORK_DIR}/build/consumer_runtime_cxx17)
  run_step("run consumer_pack" ${WORK_DIR}/build/consumer_pack)
  run_step("run consumer_weather" ${WORK_DIR}/build/consumer_weather)
  if(WITH_LOADER)
    run_step("run consumer_loader" ${WORK_DIR}/build/consumer_loader)
  endif()
endif()
