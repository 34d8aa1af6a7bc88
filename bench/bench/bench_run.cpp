// traceCondition: the truth and camera frames of one condition, which every accuracy section starts from.
#include "bench_run.h"

#include "gusuku_bake/camera_frame.h"

namespace gusuku::bench {

ConditionFrames traceCondition(TruthRenderer& renderer, const BenchView& view, uint32_t width, uint32_t height,
                               const BenchCondition& condition, uint32_t samples) {
    TracedFrameRequest request = truthRequest(view, width, height, condition, samples, 1);
    ConditionFrames frames;
    TracedFrame truth = renderer.render(request);
    request.include_building = false;
    TracedFrame camera = renderer.render(request);
    frames.trace_seconds = truth.trace_seconds + camera.trace_seconds;
    frames.truth = std::move(truth.linear);
    frames.camera = std::move(camera.linear);
    frames.exposure = bake::middleGreyExposure(frames.camera);
    return frames;
}

RespondedFrames respondedFrames(const ConditionFrames& frames, const CameraResponse& response) {
    RespondedFrames responded;
    responded.truth = applyCameraResponse(frames.truth, frames.exposure, response);
    responded.camera = applyCameraResponse(frames.camera, frames.exposure, response);
    responded.mask = changedPixelMask(responded.truth, responded.camera);
    return responded;
}

}  // namespace gusuku::bench
