// gusuku-view's window (see view_app.h).

#include "view_app.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <thread>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "bakeset_site.h"
#include "gusuku/assets/bakeset_loader.h"
#include "camera_image.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/pack_loader/runtime_pack.h"
#include "runtime_modes.h"
#include "view_modes.h"
#include "view_overlay.h"

namespace gusuku::view {

namespace {

using Clock = std::chrono::steady_clock;
// The view has stopped moving this long: trace the background for it.
constexpr double kSettleSeconds = 0.35;
constexpr double kDegreesPerPixel = 0.3;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

ViewApp* appOf(GLFWwindow* window) { return static_cast<ViewApp*>(glfwGetWindowUserPointer(window)); }

std::string sessionImagePath(const Session& session, size_t index) {
    return (std::filesystem::path(session.folder) / session.frames[index].image).string();
}

// A runtime pack folder (pack.bin) or a bake set folder.
BakeSetData loadBakeSetOrPack(const std::string& folder) {
    if (std::filesystem::exists(std::filesystem::path(folder) / "pack.bin")) return loadRuntimePack(folder);
    return loadBakeSet(folder);
}

}  // namespace

ViewApp::ViewApp(const ViewRequest& request) : request_(request) {
    if (request.actions) {
        script_ = parseViewActions(*request.actions);
        scripted_ = true;
    }
    if (isSessionFolder(request.bake_set)) {
        // Played as --render composites it: the bake set is the one session.json names.
        session_ = readSession(request.bake_set);
        const std::optional<std::string> named = sessionBakeSet(*session_);
        if (!named)
            throw InputError((std::filesystem::path(request.bake_set) / "session.json").string(), "/bake_set",
                             "missing: the session names no bake set to composite");
        request_.bake_set = *named;
        session_playing_ = !scripted_;  // a script steps it with `frame N`
    }
    bake_set_ = loadBakeSetOrPack(request_.bake_set);
    state_.position_enu = request.position_enu;
    state_.look_at_enu = request.look_at_enu;
    state_.horizontal_fov_deg = request.horizontal_fov_deg;
    state_.utc_seconds = request.time_iso ? parseIso8601Utc(*request.time_iso) : siteMidnightUtc() + 12 * 3600.0;
    state_.cloud_cover = request.cloud_cover;
    state_.mode_index = *viewModeIndex(request.mode);
    state_.msaa_samples = request.msaa_samples;
    if (session_) showSessionFrame(0);
    if (session_)
        background_ = Background::photo(sessionImagePath(*session_, 0), 1.0f);  // each row states its exposure
    else if (request.camera == "sample")
        background_ = Background::traced(
            bench_common::siteJsonOf(request_.bake_set, bake_set_.manifest, request.site_json), request.width,
            request.height, request.camera_samples, request.exposure.value_or(0.0f));
    else
        background_ = Background::photo(request.camera, request.exposure.value_or(0.0f));

    window_ = std::make_unique<WindowDevice>(background_->width(), background_->height(), "gusuku-view");
    GLFWwindow* window = window_->window();
    glfwSetWindowUserPointer(window, this);
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
        appOf(w)->onKey(key, action, mods);
    });
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) { appOf(w)->onCursor(x, y); });
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
        appOf(w)->onButton(button, action);
    });
    glfwSetScrollCallback(window, [](GLFWwindow* w, double, double y) { appOf(w)->onScroll(y); });
    glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) { appOf(w)->onResize(); });
    glfwSetWindowRefreshCallback(window, [](GLFWwindow* w) { appOf(w)->onRefresh(); });

    swapchain_ = std::make_unique<Swapchain>(window_->gpu().physical_device, window_->device(), window_->surface());
    swapchain_->recreate({background_->width(), background_->height()});
    openRuntime();
    loop_ = std::make_unique<FrameLoop>(*window_, *swapchain_, *runtime_, background_->width(), background_->height());
    std::fprintf(stderr, "gusuku-view: device %s, frame %ux%u, window %ux%u\n", window_->deviceName().c_str(),
                 background_->width(), background_->height(), swapchain_->extent().width,
                 swapchain_->extent().height);
}

ViewApp::~ViewApp() {
    if (loop_) loop_->waitIdle();
    loop_.reset();
    runtime_.reset();  // before the device it runs on
    swapchain_.reset();
    window_.reset();
}

double ViewApp::siteMidnightUtc() const {
    return bench_common::bakeDateMidnightUtc(request_.bake_set, bake_set_.manifest, "--time");
}

void ViewApp::openRuntime() {
    RuntimeOptions options;
    options.frame_width = background_->width();
    options.frame_height = background_->height();
    options.msaa_samples = state_.msaa_samples;
    options.frames_in_flight = FrameLoop::kFramesInFlight;
    if (loop_) loop_->waitIdle();
    runtime_.reset();
    runtime_ = Runtime::open(window_->gpu(), bake_set_, options);
    if (loop_) loop_->setRuntime(*runtime_);
    have_passes_ = false;
}

FrameInput ViewApp::frameInput() const {
    const bench::RuntimeMode mode = bench::runtimeModeNamed(kViewModeNames[state_.mode_index]);
    if (session_) {  // the track's row, exactly as --render composites it (view_render_session.cpp)
        const SessionFrame& row = session_->frames[session_index_];
        FrameInput frame = bench::frameInputFor(mode, {}, session_->intrinsics, row.pose, row.utc_seconds,
                                                row.cloud_cover, row.exposure.value_or(1.0f));
        frame.camera_rgba8 = nullptr;  // the frame loop puts the camera on the GPU itself
        return frame;
    }
    FrameInput frame;
    frame.intrinsics =
        CameraIntrinsics::fromFieldOfView(background_->width(), background_->height(), state_.horizontal_fov_deg);
    frame.pose = CameraPose::lookingAt(state_.position_enu, state_.look_at_enu);
    frame.utc_unix_seconds = state_.utc_seconds;
    frame.weather.cloud_cover = state_.cloud_cover;
    frame.exposure = background_->exposure();
    frame.mode = mode.mode;
    frame.colour_match = mode.colour_match;
    frame.blend_slots = mode.blend_slots;
    frame.ground_ratio = mode.ground_ratio;
    return frame;
}

void ViewApp::moved() {
    changed_ = true;
    background_stale_ = true;
    last_change_ = Clock::now();
}

// The background for the view as it is now. Traced on a thread of its own (the tracer has its own device,
// view_background.h), so the window keeps answering while it runs: started once the view has been still for
// kSettleSeconds, taken when it is done if the view has not moved since (else a new one starts). `now` (scripted
// input, R, the first frame) waits for it.
void ViewApp::refreshBackgroundIfDue(bool now) {
    if (!background_stale_ && !pending_trace_.valid()) return;
    if (session_) {  // the frame's own camera image, read when it is shown
        render_cli::CameraImage image = render_cli::readCameraImage(sessionImagePath(*session_, session_index_));
        if (image.width != background_->width() || image.height != background_->height())
            throw InputError(session_->frames[session_index_].image, "", "is not the intrinsics' size");
        loop_->setCamera(image.srgb_rgba8);
        have_background_ = true;
        background_stale_ = false;
        changed_ = true;
        return;
    }
    if (!pending_trace_.valid()) {
        if (background_->isTraced() && !now && have_background_ &&
            (dragging_ || secondsSince(last_change_) < kSettleSeconds))
            return;
        traced_for_ = {state_.position_enu, state_.look_at_enu, state_.horizontal_fov_deg};
        traced_condition_ = {state_.utc_seconds, state_.cloud_cover};
        Background* background = background_.get();
        const bench::BenchView view = traced_for_;
        const bench::BenchCondition condition = traced_condition_;
        pending_trace_ = std::async(std::launch::async, [background, view, condition] {
            double seconds = 0.0;
            std::vector<uint8_t> frame = background->frameFor(view, condition, seconds);
            if (seconds > 0.0) std::fprintf(stderr, "gusuku-view: background traced in %.1f s\n", seconds);
            return frame;
        });
    }
    if (!now && have_background_ &&
        pending_trace_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return;
    loop_->setCamera(pending_trace_.get());  // the first frame's exposure is fixed from here on
    have_background_ = true;
    changed_ = true;
    const bool same = traced_for_.position_enu == state_.position_enu &&
                      traced_for_.look_at_enu == state_.look_at_enu &&
                      traced_for_.horizontal_fov_deg == state_.horizontal_fov_deg &&
                      traced_condition_.utc_seconds == state_.utc_seconds &&
                      traced_condition_.cloud_cover == state_.cloud_cover;
    background_stale_ = !same;  // moved while it traced: trace again once the view settles
    profile_due_ = !scripted_ && same;
}

bool ViewApp::drawOnce(Screenshot* screenshot) {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_->window(), &width, &height);
    // Minimised (iconified on X11 keeps its size; elsewhere the size drops to 0): nothing to draw on.
    if (width == 0 || height == 0 || glfwGetWindowAttrib(window_->window(), GLFW_ICONIFIED)) return false;
    refreshBackgroundIfDue(scripted_ || !have_background_);
    const Clock::time_point start = Clock::now();
    FrameInfo info;
    for (int attempt = 0; attempt < 3; ++attempt) {
        if (swapchain_stale_ || attempt > 0) {
            loop_->waitIdle();  // the old images may still be in use
            if (!swapchain_->recreate({uint32_t(width), uint32_t(height)})) return false;
            swapchain_stale_ = false;
            std::fprintf(stderr, "gusuku-view: swapchain %ux%u (made %u times)\n", swapchain_->extent().width,
                         swapchain_->extent().height, swapchain_->generation());
        }
        if (loop_->drawFrame(frameInput(), info, screenshot) || (screenshot && screenshot->width)) break;
    }
    changed_ = false;
    last_info_ = info;
    last_frame_ms_ = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    updateTitle(info, last_frame_ms_);
    return true;
}

// Each pass submitted and waited for alone (renderFrameProfiled): slow, so only once the view has settled, after
// a frame has put the camera on the GPU.
void ViewApp::profilePasses() {
    FrameInput frame = frameInput();
    frame.camera_image = loop_->cameraImage();
    frame.camera_image_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    loop_->waitIdle();
    runtime_->renderFrameProfiled(frame, nullptr, passes_);
    have_passes_ = true;
    profile_due_ = false;
    updateTitle(last_info_, last_frame_ms_);
}

// The same figures in the window's title (one line) and in the overlay (a line each).
void ViewApp::updateTitle(const FrameInfo& info, double frame_ms) {
    auto slotName = [&](int slot) { return slot >= 0 ? bake_set_.manifest.slots[size_t(slot)].name : std::string("-"); };
    const double sunny = 1.0 - info.overcast_weight;
    std::vector<std::string> lines;
    char text[512];
    std::snprintf(text, sizeof text, "%s msaa %u | %s", kViewModeNames[state_.mode_index], state_.msaa_samples,
                  formatIso8601(state_.utc_seconds, bake_set_.manifest.site.utc_offset_minutes).substr(0, 16).c_str());
    lines.push_back(text);
    std::snprintf(text, sizeof text, "sun az %.1f el %.1f", info.sun_azimuth_deg, info.sun_apparent_elevation_deg);
    lines.push_back(text);
    std::snprintf(text, sizeof text, "slots %s %.2f %s %.2f %s %.2f", slotName(info.slot_a).c_str(),
                  info.slot_a >= 0 ? sunny * (1.0 - info.slot_b_weight) : 0.0, slotName(info.slot_b).c_str(),
                  info.slot_b >= 0 ? sunny * info.slot_b_weight : 0.0, slotName(info.overcast_slot).c_str(),
                  double(info.overcast_weight));
    lines.push_back(text);
    std::snprintf(text, sizeof text, "cloud %.2f (%s) | frame %.0f ms", double(state_.cloud_cover),
                  state_.weather_source.c_str(), frame_ms);
    lines.push_back(text);
    if (have_passes_) {
        std::snprintf(text, sizeof text,
                      "passes ms: shadow %.1f occluder %.1f building %.1f ground %.1f statistics %.1f",
                      passes_.shadow_ms, passes_.occluder_ms, passes_.building_ms, passes_.ground_ms,
                      passes_.statistics_ms);
        lines.push_back(text);
    }
    if (background_stale_ && background_->isTraced()) lines.push_back("tracing the background when the view stops");
    std::string title = "gusuku-view";
    for (const std::string& line : lines) title += " | " + line;
    glfwSetWindowTitle(window_->window(), title.c_str());
    // Twice the font's size where the window is wide enough for it, so that it reads on a high-density screen.
    const uint32_t scale = swapchain_ && swapchain_->extent().width >= 1000 ? 2 : 1;
    if (loop_) loop_->setOverlay(state_.overlay ? rasteriseOverlay(lines, scale) : OverlayImage{});
}

}  // namespace gusuku::view
