#pragma once
// gusuku-view's window: the bake set opened in the runtime on the window's device, the background, the input
// (mouse, keys, or scripted actions) and the title's overlay, around the frame loop (view_frame_loop.h).

#include <chrono>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/runtime/runtime.h"
#include "view_background.h"
#include "view_controls.h"
#include "view_device.h"
#include "view_frame_loop.h"
#include "view_request.h"
#include "view_script.h"
#include "view_session.h"
#include "view_swapchain.h"

namespace gusuku::view {

class ViewApp {
public:
    explicit ViewApp(const ViewRequest& request);
    ~ViewApp();
    /// Runs until the window closes (or the script ends); the exit status.
    int run();

    // Input, from GLFW's callbacks.
    void onKey(int key, int action, int mods);
    void onCursor(double x, double y);
    void onButton(int button, int action);
    void onScroll(double ticks);
    void onResize() { swapchain_stale_ = true; changed_ = true; }
    void onRefresh() { changed_ = true; }

private:
    void openRuntime();
    void moved();
    void refreshBackgroundIfDue(bool now);
    bool tracing() const { return pending_trace_.valid(); }
    bool drawOnce(Screenshot* screenshot);
    void runAction(const ViewAction& action);
    void resizeWindow(unsigned width, unsigned height);
    void screenshotTo(const std::string& path);
    void updateTitle(const FrameInfo& info, double frame_ms);
    void profilePasses();
    FrameInput frameInput() const;
    double siteMidnightUtc() const;
    void showSessionFrame(size_t index);
    void advanceSessionIfDue();

    /// A recorded session played (docs/view.md): each frame's camera image is the background and its track row
    /// the pose, instant, cover and exposure; orbit, walk, the hour and the cover keys do nothing while one plays.
    std::optional<Session> session_;
    size_t session_index_ = 0;
    bool session_playing_ = true;
    std::chrono::steady_clock::time_point session_shown_{};

    ViewRequest request_;
    BakeSetData bake_set_;
    std::unique_ptr<Background> background_;
    std::unique_ptr<WindowDevice> window_;
    std::unique_ptr<Swapchain> swapchain_;
    std::unique_ptr<Runtime> runtime_;
    std::unique_ptr<FrameLoop> loop_;
    ViewState state_;
    std::vector<ViewAction> script_;
    size_t next_action_ = 0;
    bool scripted_ = false;
    bool changed_ = true;          ///< something to draw
    bool background_stale_ = true;  ///< the view, instant or cover changed since the background was traced
    bool swapchain_stale_ = false;
    bool dragging_ = false;
    double drag_x_ = 0.0, drag_y_ = 0.0;
    std::chrono::steady_clock::time_point last_change_{};
    PassTimings passes_{};
    bool have_passes_ = false;
    bool profile_due_ = false;  ///< time the passes once the next frame is drawn (the view has settled)
    FrameInfo last_info_{};
    double last_frame_ms_ = 0.0;
    /// The background being traced (view_background.h: its own device, so its own thread), and for what; declared
    /// after background_ so that it is waited for before the background goes.
    std::future<std::vector<uint8_t>> pending_trace_;
    bench::BenchView traced_for_;
    bench::BenchCondition traced_condition_;
    bool have_background_ = false;  ///< the camera image holds a background
    uint32_t screenshot_count_ = 0;
};

}  // namespace gusuku::view
