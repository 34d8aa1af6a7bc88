#include "render_outputs.h"

#include <filesystem>
#include <system_error>
#include <utility>

#include "gusuku/formats/input_error.h"
#include "gusuku_bake/output_guard.h"

namespace gusuku::render_cli {
namespace {

namespace fs = std::filesystem;

// The path as the file system will resolve it: links followed where they exist, "." and ".." folded, so that
// "set/../set/building_overcast.exr" and a link to it compare equal to the file itself.
fs::path resolved(const std::string& path) {
    std::error_code error;
    fs::path canonical = fs::weakly_canonical(fs::absolute(path), error);
    return error ? fs::absolute(path).lexically_normal() : canonical;
}

}  // namespace

std::vector<std::string> renderInputFiles(const RenderRequest& request, const std::string& site_json) {
    std::vector<std::string> inputs;
    std::error_code error;
    for (fs::directory_iterator entry(request.bake_set, error), end; !error && entry != end; entry.increment(error))
        inputs.push_back(entry->path().string());
    if (request.camera != "sample") inputs.push_back(request.camera);
    if (!site_json.empty()) inputs.push_back(site_json);
    return inputs;
}

void refuseOutputsThatAreInputs(const RenderRequest& request, const std::vector<std::string>& inputs) {
    std::vector<std::pair<std::string, std::string>> outputs = {{"-o", request.output_png}};
    if (request.direct_only_png) outputs.push_back({"--direct-only", *request.direct_only_png});
    if (request.camera_png) outputs.push_back({"--camera-out", *request.camera_png});
    const fs::path bake_set = resolved(request.bake_set);
    for (size_t index = 0; index < outputs.size(); ++index) {
        const auto& [option, path] = outputs[index];
        const fs::path output = resolved(path);
        if (output == bake_set)
            throw InputError(path, option, "is the bake set folder; write the image elsewhere");
        for (const std::string& input : inputs)
            if (output == resolved(input))
                throw InputError(path, option, "is an input of this render (" + input +
                                                   "); writing it would destroy it, so nothing was rendered");
        for (size_t other = 0; other < index; ++other)
            if (output == resolved(outputs[other].second))
                throw InputError(path, option, "is also the " + outputs[other].first +
                                                   " output; each output needs its own file");
        // The rule every writing command shares (gusuku_bake/output_guard.h): nothing inside a bake set or a
        // runtime pack, this render's own set included, which its next bake or pack would take for its own.
        bake::OutputRequest guard;
        guard.output = path;
        guard.field = option;
        guard.command = "render";
        guard.kind = bake::OutputKind::kFile;
        guard.inputs = inputs;
        guard.read_sets = {request.bake_set};
        bake::refuseUnsafeOutput(guard);
    }
}

}  // namespace gusuku::render_cli
