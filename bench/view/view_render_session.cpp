// A session composited headless into PNG frames (see view_render_session.h).

#include "view_render_session.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "camera_image.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "frame_progress.h"
#include "view_apng.h"
#include "runtime_modes.h"

namespace gusuku::view {
namespace fs = std::filesystem;

namespace {

fs::path resolved(const std::string& path) {
    std::error_code error;
    const fs::path canonical = fs::weakly_canonical(fs::absolute(path), error);
    return error ? fs::absolute(path).lexically_normal() : canonical;
}

// True when `inner` is `outer` or lies inside it.
bool isWithin(const fs::path& inner, const fs::path& outer) {
    auto outer_part = outer.begin(), inner_part = inner.begin();
    for (; outer_part != outer.end(); ++outer_part, ++inner_part)
        if (inner_part == inner.end() || *inner_part != *outer_part) return outer_part->empty();
    return true;
}

// Places two frames side by side (each width x height RGBA8) in one 2 * width x height frame.
std::vector<uint8_t> besideEachOther(const std::vector<uint8_t>& left, const std::vector<uint8_t>& right,
                                     uint32_t width, uint32_t height) {
    std::vector<uint8_t> both(size_t(width) * 2 * height * 4);
    const size_t row_bytes = size_t(width) * 4;
    for (uint32_t row = 0; row < height; ++row) {
        std::memcpy(&both[row * row_bytes * 2], &left[row * row_bytes], row_bytes);
        std::memcpy(&both[row * row_bytes * 2 + row_bytes], &right[row * row_bytes], row_bytes);
    }
    return both;
}

}  // namespace

bool isAnimatedOutput(const std::string& out) { return fs::path(out).extension() == ".png"; }

std::string outputFrameName(size_t index) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06zu.png", index);
    return name;
}

void refuseOutputOverInputs(const std::string& out, const std::string& option, const std::vector<std::string>& inputs) {
    const fs::path written = resolved(out);
    for (const std::string& input : inputs) {
        if (input.empty()) continue;
        const fs::path read = resolved(input);
        if (isWithin(written, read) || isWithin(read, written))
            throw InputError(out, option, "is or holds " + input + ", which this run reads; write elsewhere");
    }
}

void refuseUnsafeRenderFolder(const std::string& out_folder, const std::string& session_folder,
                              const std::string& bake_set_folder) {
    refuseOutputOverInputs(out_folder, "--render", {session_folder, bake_set_folder});
    const fs::path out = resolved(out_folder);
    std::error_code error;
    if (!fs::exists(out, error)) return;
    if (isAnimatedOutput(out_folder)) {
        if (!fs::is_regular_file(out, error))
            throw InputError(out_folder, "--render", "exists and is not a file; not overwritten");
        return;
    }
    if (!fs::is_directory(out, error))
        throw InputError(out_folder, "--render", "exists and is not a folder; not overwritten");
    for (const fs::directory_entry& entry : fs::directory_iterator(out, error)) {
        const std::string name = entry.path().filename().string();
        if (!(name.rfind("frame_", 0) == 0 && entry.path().extension() == ".png" && entry.is_regular_file()))
            throw InputError(out_folder, "--render",
                             "holds " + name + ", not a previous render's frame; not overwritten");
    }
}

size_t renderSession(const GpuDevice& gpu, const BakeSetData& bake_set, const Session& session,
                     const std::string& out_folder, const SessionRenderOptions& options) {
    const bench::RuntimeMode mode = bench::runtimeModeNamed(options.mode);
    const bench::RuntimeMode direct_only = bench::runtimeModeNamed("direct_only");
    const uint32_t width = session.intrinsics.width, height = session.intrinsics.height;
    RuntimeOptions runtime_options;
    runtime_options.frame_width = width;
    runtime_options.frame_height = height;
    runtime_options.msaa_samples = options.msaa_samples;
    std::unique_ptr<Runtime> runtime = Runtime::open(gpu, bake_set, runtime_options);

    const fs::path final_path = fs::absolute(out_folder).lexically_normal();
    const bool animated = isAnimatedOutput(out_folder);
    const fs::path temporary =
        final_path.parent_path() / ("." + final_path.filename().string() + ".tmp-" + std::to_string(getpid()));
    std::error_code error;
    fs::remove_all(temporary, error);
    fs::create_directories(temporary, error);
    if (error) throw InputError(out_folder, "--render", "cannot create the folder: " + error.message());
    FrameProgress progress(session.frames.size(), options.show_progress);
    try {
        std::vector<uint8_t> composite(size_t(width) * height * 4), direct(composite.size());
        for (size_t index = 0; index < session.frames.size(); ++index) {
            const SessionFrame& row = session.frames[index];
            std::vector<uint8_t> camera = row.rgba8;
            if (camera.empty()) {
                render_cli::CameraImage image = render_cli::readCameraImage((fs::path(session.folder) / row.image).string());
                if (image.width != width || image.height != height)
                    throw InputError(row.image, "", "is not the intrinsics' size");
                camera = std::move(image.srgb_rgba8);
            }
            const float exposure = row.exposure.value_or(1.0f);
            runtime->renderFrame(frameInputFor(mode, camera, session.intrinsics, row.pose, row.utc_seconds,
                                               row.cloud_cover, exposure),
                                 composite.data());
            std::vector<uint8_t> picture = composite;
            if (options.beside_direct_only) {
                runtime->renderFrame(frameInputFor(direct_only, camera, session.intrinsics, row.pose,
                                                   row.utc_seconds, row.cloud_cover, exposure),
                                     direct.data());
                picture = besideEachOther(composite, direct, width, height);
            }
            writePngRgba8((temporary / outputFrameName(index)).string(),
                          int(options.beside_direct_only ? width * 2 : width), int(height), picture);
            progress.advance(index + 1);
        }
        if (animated) {
            std::vector<std::string> frame_files;
            for (size_t index = 0; index < session.frames.size(); ++index)
                frame_files.push_back((temporary / outputFrameName(index)).string());
            writeApng(frame_files, final_path.string());  // atomically: the previous file stays until it is whole
            fs::remove_all(temporary, error);
            return session.frames.size();
        }
        // The previous render goes only once this one is whole.
        const fs::path old =
            final_path.parent_path() / ("." + final_path.filename().string() + ".old-" + std::to_string(getpid()));
        if (fs::exists(final_path)) fs::rename(final_path, old);
        fs::rename(temporary, final_path);
        fs::remove_all(old, error);
    } catch (...) {
        fs::remove_all(temporary, error);
        throw;
    }
    return session.frames.size();
}

}  // namespace gusuku::view
