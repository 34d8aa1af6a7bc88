# cmake -DBUILD_DIR=... -DCONSUMER_SOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=... -DC_COMPILER=... -DCXX_COMPILER=...
#       -P install_and_consume.cmake
# Installs the build into WORK_DIR/prefix (both components; the runtime component alone into another prefix, to
# check the split), configures and builds the consumer against that prefix alone (CMAKE_PREFIX_PATH), and runs its
# two programs. Any step failing fails the test.
foreach(variable BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR GENERATOR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "install_and_consume.cmake: ${variable} is not set")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run_step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  message(STATUS "${name}:\n${output}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${name} failed (${result})")
  endif()
endfunction()

run_step("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(expected include/gusuku/runtime/gusuku.h include/gusuku/runtime/runtime.h include/gusuku/loader/gusuku_loader.h
        lib/cmake/gusuku/gusukuConfig.cmake lib/cmake/gusuku/gusukuConfigVersion.cmake)
  if(NOT EXISTS ${prefix}/${expected})
    message(FATAL_ERROR "install: ${expected} is missing from the prefix")
  endif()
endforeach()
file(GLOB interface_headers ${prefix}/include/*_interface.h ${prefix}/include/gusuku/*_interface.h)
if(interface_headers)
  message(FATAL_ERROR "install: shader interface headers are private, yet installed: ${interface_headers}")
endif()

# The runtime component alone: the lean libraries and the package, nothing of the loader's I/O stack.
run_step("install the runtime component" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/runtime_only
         --component runtime)
foreach(absent lib/libgusuku_assets.a lib/libgusuku_loader.a lib/cmake/gusuku/gusukuLoaderTargets.cmake)
  if(EXISTS ${WORK_DIR}/runtime_only/${absent})
    message(FATAL_ERROR "install --component runtime: ${absent} belongs to the loader component")
  endif()
endforeach()
if(NOT EXISTS ${WORK_DIR}/runtime_only/lib/libgusuku_runtime.a)
  message(FATAL_ERROR "install --component runtime: lib/libgusuku_runtime.a is missing")
endif()
# Headers by library: the runtime component carries the headers of the libraries it installs and no others.
foreach(folder maths gpu runtime)
  if(NOT IS_DIRECTORY ${WORK_DIR}/runtime_only/include/gusuku/${folder})
    message(FATAL_ERROR "install --component runtime: include/gusuku/${folder}/ is missing")
  endif()
endforeach()
file(GLOB runtime_only_entries RELATIVE ${WORK_DIR}/runtime_only/include/gusuku ${WORK_DIR}/runtime_only/include/gusuku/*)
list(REMOVE_ITEM runtime_only_entries maths gpu runtime)
if(runtime_only_entries)
  message(FATAL_ERROR "install --component runtime: include/gusuku/ also holds ${runtime_only_entries}, "
                      "headers of libraries the component does not install")
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
run_step("configure the consumer" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
         -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix} ${compilers}
         "-DGUSUKU_INSTALLED_HEADERS=${installed_headers_joined}")
run_step("build the consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run_step("run consumer_runtime" ${WORK_DIR}/build/consumer_runtime)
run_step("run consumer_loader" ${WORK_DIR}/build/consumer_loader)
