#pragma once
// gusuku-view's scripted input (--actions): what a test drives the window with, deterministically. A list of
// actions separated by ';', each a verb and its argument:
//   orbit DEG, pitch DEG, walk M    the camera moves of view_controls.h (the background is traced again at once)
//   hour H                          the site clock's hour on the bake date, [0, 24)
//   time ISO8601                    an instant, with its offset
//   weather C                       the cloud cover, [0, 1]
//   mode M                          a mode of view_modes.h
//   msaa N                          RuntimeOptions::msaa_samples (the runtime is opened again)
//   frame N                         a played session's frame N (from 0), paused there
//   frames N                        N frames drawn as they are, [1, 1000]
//   resize WxH                      the window resized (the swapchain is made again)
//   screenshot PNG                  the window's pixels of the next frame presented, as an sRGB PNG
//   quit                            close (also after the last action)
// Every action is checked when the command line is read: a bad one is refused before a window opens.

#include <string>
#include <vector>

namespace gusuku::view {

struct ViewAction {
    std::string verb;
    std::string text;    ///< the argument as written
    double number = 0.0;  ///< the argument as a number, for numeric verbs
    unsigned width = 0, height = 0;  ///< resize
};

/// Parses --actions; OptionValueError "gusuku-view: --actions: ..." naming the action and what is wrong.
std::vector<ViewAction> parseViewActions(const std::string& text);

}  // namespace gusuku::view
