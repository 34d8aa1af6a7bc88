// gusuku-view's headless runs (see view_session_command.h).

#include "view_session_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/gpu/vulkan_context.h"
#include "sample_session.h"
#include "view_render_session.h"
#include "view_session.h"

namespace gusuku::view {
namespace fs = std::filesystem;

namespace {

SampleWalkOptions walkOptions(const ViewRequest& request) {
    SampleWalkOptions options;
    options.frames = request.walk_frames;
    options.width = request.walk_width;
    options.height = request.walk_height;
    options.samples_per_pixel = request.walk_samples;
    return options;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int writeSampleSession(const ViewRequest& request) {
    const std::string& out = *request.sample_session_out;
    const BakeSetData bake_set = loadBakeSet(request.bake_set);
    // The session never goes into (or holds) the bake set it names.
    refuseOutputOverInputs(out, "--sample-session", {request.bake_set});
    if (fs::exists(out) && !isSessionFolder(out) && !(fs::is_directory(out) && fs::is_empty(out)))
        throw InputError(out, "--sample-session", "exists and is not a session folder; not overwritten");
    VulkanContext context(vulkanOptionsFromEnvironment());
    const auto start = std::chrono::steady_clock::now();
    const Session session = makeSampleSession(context, request.bake_set, bake_set, walkOptions(request));
    writeSession(out, session, request.bake_set);
    std::printf("sample session:  %s, %zu frames %u x %u, %s to %s, traced in %.1f s\n", out.c_str(),
                session.frames.size(), session.intrinsics.width, session.intrinsics.height,
                session.frames.front().time_iso.c_str(), session.frames.back().time_iso.c_str(), secondsSince(start));
    return 0;
}

int renderToFrames(const ViewRequest& request) {
    const std::string& out = *request.render_out;
    const std::string& input = request.bake_set;
    const bool from_session = isSessionFolder(input);
    std::optional<Session> session;
    std::string bake_set_folder = input;
    if (from_session) {
        session = readSession(input);  // every row and every frame's header checked before anything is written
        const std::optional<std::string> named = sessionBakeSet(*session);
        if (!named)
            throw InputError((fs::path(input) / "session.json").string(), "/bake_set",
                             "missing: the session names no bake set to composite");
        bake_set_folder = *named;
    }
    const BakeSetData bake_set = loadBakeSet(bake_set_folder);
    refuseUnsafeRenderFolder(out, from_session ? input : "", bake_set_folder);
    VulkanContext context(vulkanOptionsFromEnvironment());
    std::fprintf(stderr, "gusuku-view: device %s\n", context.deviceDescription().c_str());
    if (!session) session = makeSampleSession(context, bake_set_folder, bake_set, walkOptions(request));
    SessionRenderOptions options;
    options.mode = request.mode;
    options.beside_direct_only = request.beside_direct_only;
    options.msaa_samples = request.msaa_samples;
    const auto start = std::chrono::steady_clock::now();
    const size_t frames = renderSession(context, bake_set, *session, out, options);
    std::printf("frames:          %zu in %s (%u x %u, %s%s), %.1f s\n", frames, out.c_str(),
                session->intrinsics.width * (request.beside_direct_only ? 2 : 1), session->intrinsics.height,
                request.mode.c_str(), request.beside_direct_only ? " beside direct_only" : "", secondsSince(start));
    return 0;
}

}  // namespace

int runHeadless(const ViewRequest& request) {
    return request.sample_session_out ? writeSampleSession(request) : renderToFrames(request);
}

}  // namespace gusuku::view
