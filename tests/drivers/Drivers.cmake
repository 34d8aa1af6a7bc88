# The runtime's tests on a second Vulkan driver: SwiftShader (Google's CPU Vulkan, the Android emulator's), which
# Debian's chromium package ships. Each executable below runs a second time, with validation on, through
# run_on_driver.sh, which restricts the loader to SwiftShader's ICD (VK_ICD_FILENAMES) and skips (77) saying so
# when the ICD is absent. `ctest -L swiftshader` runs them alone. docs/development.md's Drivers section says what
# each driver shows and what they cost: about a minute of ctest on 2 cores. One golden per image serves both
# drivers (tests/test_runtime_golden.cpp states the tolerance and SwiftShader's measured difference).
set(GUSUKU_SWIFTSHADER_ICD /usr/lib/chromium/vk_swiftshader_icd.json CACHE FILEPATH
    "SwiftShader's Vulkan ICD manifest, for the swiftshader_* tests (absent: they skip)")
set(GUSUKU_RUN_ON_DRIVER ${CMAKE_CURRENT_SOURCE_DIR}/drivers/run_on_driver.sh)

# Executable, then its arguments (a GoogleTest filter where part of it is left to lavapipe, with the reason).
set(GUSUKU_SWIFTSHADER_TESTS
    "test_runtime_golden"
    "test_runtime_camera_formats"
    # The zero-copy camera: SwiftShader has samplerYcbcrConversion, lavapipe does not (there it tests the refusal).
    "test_runtime_zero_copy_camera"
    "test_runtime_app_device"  # the app's own device and frames in flight
    "test_runtime_msaa"
    "test_runtime_mipmaps"
    "test_runtime_alpha_mask"
    "test_runtime_lightmap_formats"
    "test_runtime_error_categories"
    "test_runtime_pack"
    "test_runtime_pack_astc"
    "test_runtime_pack_astc_textures"
    "test_colour_match"
    "test_vulkan"
    "test_gpu_device"
    # Two of its seven cases: the host-bytes path and the GPU-resident one with kAuto's ground match (seven cost
    # 27 s of CPU on SwiftShader).
    "test_runtime_allocations --gtest_filter=*/proposed:*/proposed_auto_gpu_resident"
    "test_c_api_versions"
    # The C programs print validation messages rather than failing on them (the GoogleTest ones fail the test
    # themselves, and some print messages they provoke on purpose): these two fail on the message.
    "test_c_api"
    "readme_example")
# Left out of CI for its 30 minutes (each passes on SwiftShader: `bash tests/drivers/run_on_driver.sh ICD EXE`):
# test_runtime_shadows (39 s there), test_runtime (17 s) and test_colour_match_ground (15 s), whose paths the
# goldens, the allocations and the camera formats above draw too.
# Left to lavapipe: test_runtime_alpha_coverage's far masked quad (SwiftShader's alpha to coverage keeps 0.261 of
# the leaves' 0.324 share at 12 m and msaa 4 where lavapipe keeps 0.332, outside the test's 0.04; open in
# docs/development.md's Drivers section), and the slow test_runtime_memory (28 s of CPU on SwiftShader).
foreach(entry ${GUSUKU_SWIFTSHADER_TESTS})
  separate_arguments(arguments UNIX_COMMAND "${entry}")
  list(POP_FRONT arguments executable)
  add_test(NAME swiftshader_${executable}
           COMMAND ${GUSUKU_BASH} ${GUSUKU_RUN_ON_DRIVER} ${GUSUKU_SWIFTSHADER_ICD} $<TARGET_FILE:${executable}>
                   ${arguments})
  set_tests_properties(swiftshader_${executable} PROPERTIES ENVIRONMENT "GUSUKU_VALIDATION=1"
                       SKIP_RETURN_CODE 77 LABELS swiftshader)
  if(executable MATCHES "^(test_c_api|readme_example)$")
    set_tests_properties(swiftshader_${executable} PROPERTIES FAIL_REGULAR_EXPRESSION "Vulkan validation")
  endif()
endforeach()

# SwiftShader's crash when a device is destroyed after the driver's static destructors (the reason
# gpu_test_support.cpp releases the shared context before exit), with no gusuku in it: passes while the crash
# stands and fails, saying so, when the driver no longer crashes.
add_executable(swiftshader_exit_order ${CMAKE_CURRENT_SOURCE_DIR}/drivers/swiftshader_exit_order.cpp)
target_link_libraries(swiftshader_exit_order PRIVATE Vulkan::Vulkan)
add_test(NAME swiftshader_exit_order
         COMMAND ${GUSUKU_BASH} ${GUSUKU_RUN_ON_DRIVER} ${GUSUKU_SWIFTSHADER_ICD} $<TARGET_FILE:swiftshader_exit_order>)
set_tests_properties(swiftshader_exit_order PROPERTIES SKIP_RETURN_CODE 77 LABELS swiftshader)
