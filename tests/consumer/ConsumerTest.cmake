# The test install_and_consume (included by tests/CMakeLists.txt, and by the top-level CMakeLists.txt in a
# runtime-only build, which has no tests/ folder of its own): install this build into a fresh prefix, build
# tests/consumer against it with find_package(gusuku) and run it (a headless runtime on an in-memory bake set, one
# frame from C99 and one from C++17; the loader on a missing folder when the build has it).
if(GUSUKU_RUNTIME_ONLY)
  set(consumer_with_loader OFF)
else()
  set(consumer_with_loader ON)
endif()
add_test(NAME install_and_consume
         COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR}
                 -DCONSUMER_SOURCE_DIR=${PROJECT_SOURCE_DIR}/tests/consumer
                 -DWORK_DIR=${PROJECT_BINARY_DIR}/tests/install_and_consume
                 -DGENERATOR=${CMAKE_GENERATOR} -DC_COMPILER=${CMAKE_C_COMPILER} -DCXX_COMPILER=${CMAKE_CXX_COMPILER}
                 -DWITH_LOADER=${consumer_with_loader}
                 -P ${PROJECT_SOURCE_DIR}/tests/consumer/install_and_consume.cmake)
set_tests_properties(install_and_consume PROPERTIES ENVIRONMENT "GUSUKU_VALIDATION=1"
                     FAIL_REGULAR_EXPRESSION "Vulkan validation" TIMEOUT 300)
