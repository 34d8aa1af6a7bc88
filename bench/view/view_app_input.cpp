// gusuku-view's input and main loop: keys, mouse and scripted actions change the ViewState (view_controls.h);
// the loop draws when something changed and otherwise sleeps in glfwWaitEvents (no busy loop; a minimised
// window draws nothing).

#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "gusuku/assets/image.h"
#include "view_app.h"
#include "view_modes.h"

namespace gusuku::view {

namespace {
constexpr double kDegreesPerPixel = 0.3;
constexpr double kHourStep = 0.25;
constexpr float kCloudSteps[] = {0.0f, 0.5f, 1.0f};
// A played session's rate: the animation's (--render OUT.png), as session.json states none.
constexpr double kSessionFramesPerSecond = 4.0;

bool changesState(const ViewAction& action) {
    for (const char* verb : {"orbit", "pitch", "walk", "hour", "time", "weather", "mode"})
        if (action.verb == verb) return true;
    return false;
}
}  // namespace

// A played session's frame `index` shown (its camera image read at the next draw).
void ViewApp::showSessionFrame(size_t index) {
    session_index_ = index % session_->frames.size();
    session_shown_ = std::chrono::steady_clock::now();
    const SessionFrame& row = session_->frames[session_index_];
    state_.utc_seconds = row.utc_seconds;  // for the title
    state_.cloud_cover = row.cloud_cover;
    state_.weather_source = "session";
    background_stale_ = true;
    changed_ = true;
}

// Playing: the next frame once 1 / kSessionFramesPerSecond has passed since this one was shown; looping.
void ViewApp::advanceSessionIfDue() {
    if (!session_ || !session_playing_) return;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - session_shown_).count() >=
        1.0 / kSessionFramesPerSecond)
        showSessionFrame(session_index_ + 1);
}

void ViewApp::onKey(int key, int action, int mods) {
    if (action == GLFW_RELEASE) return;
    const double step = (mods & GLFW_MOD_SHIFT) ? 5.0 : 1.0;
    if (session_) {  // the track holds the pose, the instant and the cover: the view keys do nothing
        const size_t count = session_->frames.size();
        switch (key) {
        case GLFW_KEY_SPACE: session_playing_ = !session_playing_; showSessionFrame(session_index_); return;
        case GLFW_KEY_COMMA: session_playing_ = false; showSessionFrame(session_index_ + count - 1); return;
        case GLFW_KEY_PERIOD: session_playing_ = false; showSessionFrame(session_index_ + 1); return;
        case GLFW_KEY_W: case GLFW_KEY_S: case GLFW_KEY_A: case GLFW_KEY_D: case GLFW_KEY_LEFT: case GLFW_KEY_RIGHT:
        case GLFW_KEY_UP: case GLFW_KEY_DOWN: case GLFW_KEY_C: case GLFW_KEY_R: return;
        default: break;
        }
    }
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_->window(), GLFW_TRUE); return;
    case GLFW_KEY_W: state_.walk(step); break;
    case GLFW_KEY_S: state_.walk(-step); break;
    case GLFW_KEY_A: state_.strafe(-step); break;
    case GLFW_KEY_D: state_.strafe(step); break;
    case GLFW_KEY_LEFT: state_.orbit(-5.0 * step); break;
    case GLFW_KEY_RIGHT: state_.orbit(5.0 * step); break;
    case GLFW_KEY_UP: state_.pitch(5.0); break;
    case GLFW_KEY_DOWN: state_.pitch(-5.0); break;
    case GLFW_KEY_COMMA: state_.utc_seconds -= kHourStep * 3600.0 * step; break;
    case GLFW_KEY_PERIOD: state_.utc_seconds += kHourStep * 3600.0 * step; break;
    case GLFW_KEY_C: {
        size_t next = 0;
        while (next < std::size(kCloudSteps) && kCloudSteps[next] <= state_.cloud_cover) ++next;
        state_.cloud_cover = kCloudSteps[next % std::size(kCloudSteps)];
        state_.weather_source = "keys";
        break;
    }
    case GLFW_KEY_M:
        state_.mode_index = (state_.mode_index + ((mods & GLFW_MOD_SHIFT) ? std::size(kViewModeNames) - 1 : 1)) %
                            std::size(kViewModeNames);
        if (bake_set_.ground_albedo.width == 0 && std::string(kViewModeNames[state_.mode_index]) ==
                                                      "proposed_ground_match")
            state_.mode_index = (state_.mode_index + 1) % std::size(kViewModeNames);  // needs ground albedo
        runtime_->resetColourStatistics();
        changed_ = true;
        return;
    case GLFW_KEY_X:
        state_.msaa_samples = state_.msaa_samples > 1 ? 1 : (request_.msaa_samples > 1 ? request_.msaa_samples : 4);
        openRuntime();
        changed_ = true;
        return;
    case GLFW_KEY_R: background_stale_ = true; refreshBackgroundIfDue(true); return;
    case GLFW_KEY_P: profile_due_ = true; changed_ = true; return;
    case GLFW_KEY_O:
        state_.overlay = !state_.overlay;
        updateTitle(last_info_, last_frame_ms_);
        changed_ = true;
        return;
    case GLFW_KEY_F12: screenshotTo("gusuku-view-" + std::to_string(++screenshot_count_) + ".png"); return;
    default: return;
    }
    moved();
}

void ViewApp::onButton(int button, int action) {
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    dragging_ = action == GLFW_PRESS;
    glfwGetCursorPos(window_->window(), &drag_x_, &drag_y_);
    if (!dragging_) last_change_ = std::chrono::steady_clock::now();  // settling starts when the button is let go
}

void ViewApp::onCursor(double x, double y) {
    if (!dragging_ || session_) return;
    state_.orbit(-(x - drag_x_) * kDegreesPerPixel);
    state_.pitch((y - drag_y_) * kDegreesPerPixel);
    drag_x_ = x;
    drag_y_ = y;
    moved();
}

void ViewApp::onScroll(double ticks) {
    if (session_) return;
    state_.dolly(0.1 * ticks);
    moved();
}

void ViewApp::screenshotTo(const std::string& path) {
    Screenshot shot;
    if (!drawOnce(&shot) || shot.width == 0) throw std::runtime_error("gusuku-view: screenshot " + path +
                                                                     ": the window has nothing to draw on (minimised)");
    writePngRgba8(path, int(shot.width), int(shot.height), shot.rgba8);
    std::printf("screenshot: %s (%ux%u)\n", path.c_str(), shot.width, shot.height);
}

// Sets the window's size and waits (up to 2 s) for the window system to apply it.
void ViewApp::resizeWindow(unsigned width, unsigned height) {
    glfwSetWindowSize(window_->window(), int(width), int(height));
    const auto start = std::chrono::steady_clock::now();
    int now_width = 0, now_height = 0;
    do {
        glfwWaitEventsTimeout(0.05);
        glfwGetFramebufferSize(window_->window(), &now_width, &now_height);
    } while ((unsigned(now_width) != width || unsigned(now_height) != height) &&
             std::chrono::steady_clock::now() - start < std::chrono::seconds(2));
    swapchain_stale_ = true;
    changed_ = true;
}

void ViewApp::runAction(const ViewAction& action) {
    const std::string& verb = action.verb;
    if (verb == "orbit") state_.orbit(action.number);
    else if (verb == "pitch") state_.pitch(action.number);
    else if (verb == "walk") state_.walk(action.number);
    else if (verb == "hour") state_.utc_seconds = siteMidnightUtc() + action.number * 3600.0;
    else if (verb == "time") state_.utc_seconds = action.number;
    else if (verb == "weather") {
        state_.cloud_cover = float(action.number);
        state_.weather_source = "script";
    } else if (verb == "mode") {
        state_.mode_index = *viewModeIndex(action.text);
        runtime_->resetColourStatistics();
    } else if (verb == "msaa") {
        state_.msaa_samples = uint32_t(action.number);
        openRuntime();
    } else if (verb == "resize") {
        resizeWindow(action.width, action.height);
    } else if (verb == "screenshot") {
        screenshotTo(action.text);
        return;
    } else if (verb == "frame") {
        if (!session_ || size_t(action.number) >= session_->frames.size())
            throw std::runtime_error("--actions: 'frame " + action.text + "': " +
                                     (session_ ? "the session has " + std::to_string(session_->frames.size()) +
                                                     " frames"
                                               : std::string("no session is played")));
        session_playing_ = false;
        showSessionFrame(size_t(action.number));
        return;
    } else if (verb == "frames") {
        for (int frame = 0; frame < int(action.number); ++frame) drawOnce(nullptr);
        return;
    } else if (verb == "quit") {
        glfwSetWindowShouldClose(window_->window(), GLFW_TRUE);
        return;
    }
    moved();
}

int ViewApp::run() {
    GLFWwindow* window = window_->window();
    while (!glfwWindowShouldClose(window)) {
        if (scripted_) {
            glfwPollEvents();
            if (next_action_ == script_.size()) break;  // the script ended: close
            runAction(script_[next_action_++]);
            // Consecutive changes of the view, instant or light are drawn once, after the last of them.
            if (changed_ && (next_action_ == script_.size() || !changesState(script_[next_action_])))
                drawOnce(nullptr);
            continue;
        }
        // Nothing to do: sleep until an event (or the settle time, for the background), never spin.
        const bool busy = background_stale_ || tracing() || (session_ && session_playing_);
        if (!changed_ && !profile_due_) glfwWaitEventsTimeout(busy ? 0.02 : 1.0);
        else glfwPollEvents();
        int width = 0, height = 0;
        glfwGetFramebufferSize(window, &width, &height);
        if (width == 0 || height == 0 || glfwGetWindowAttrib(window, GLFW_ICONIFIED)) {  // minimised: wait for it
            glfwWaitEvents();
            continue;
        }
        advanceSessionIfDue();
        refreshBackgroundIfDue(false);  // starts a trace once the view settles, takes it when done
        if (changed_) drawOnce(nullptr);
        if (profile_due_ && !changed_) profilePasses();
    }
    loop_->waitIdle();
    return WindowDevice::validationMessageCount() == 0 ? 0 : 1;
}

}  // namespace gusuku::view
