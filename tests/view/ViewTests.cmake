# gusuku-view under Xvfb (tests/view/check_view_window.py says what it checks; issue 45 item 4), included by
# tests/CMakeLists.txt. The fixture bakes the sample at 1 sample a texel; the window test opens the viewer on it,
# drives it with scripted input and holds its screenshots to gusuku-render's composite. Skipped (77) without
# xvfb-run; absent without GLFW (bench/CMakeLists.txt then builds no gusuku-view).
if(TARGET gusuku-view AND Python3_FOUND)
  set(GUSUKU_VIEW_WORK ${CMAKE_BINARY_DIR}/view-window)
  add_test(NAME view_window_bakeset
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/view/check_view_window.py bake
                   --bake $<TARGET_FILE:gusuku-bake> --work ${GUSUKU_VIEW_WORK})
  set_tests_properties(view_window_bakeset PROPERTIES FIXTURES_SETUP view_window TIMEOUT 120)
  add_test(NAME view_window
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/view/check_view_window.py window
                   --view $<TARGET_FILE:gusuku-view> --render $<TARGET_FILE:gusuku-render> --work ${GUSUKU_VIEW_WORK})
  set_tests_properties(view_window PROPERTIES FIXTURES_REQUIRED view_window ENVIRONMENT "GUSUKU_VALIDATION=1"
                       FAIL_REGULAR_EXPRESSION "Vulkan validation" SKIP_RETURN_CODE 77 TIMEOUT 120)
endif()
