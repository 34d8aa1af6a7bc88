#pragma once
// The site occluder's depth in the main pass (docs/design.md 8): the site's mesh drawn depth-only, pushed
// kOccluderPushM away from the camera, so that the camera shows through it while it hides what lies behind it.
// A FramePass (frame_pass.h). Private to gusuku_runtime.

#include "device_object.h"
#include "frame_pass.h"
#include "runtime_depth_push.h"
#include "runtime_interface.h"

namespace gusuku::runtime_detail {

class OccluderPass final : public FramePass {
public:
    /// Its pipeline, for render passes compatible with main_pass at the main pass's sample count; drop_m: how far
    /// the occluder is lowered (the bake set's simplification error, metres).
    OccluderPass(const PassContext& context, VkRenderPass main_pass, VkSampleCountFlagBits samples, float drop_m);

    /// Host side: the camera's view of this frame (occluderPushFor).
    void prepare(const shader_interface::FrameUniforms& uniforms);
    void recordInMainPass(PassRecording& recording) override;

private:
    const PassContext context_;
    PipelineLayout layout_;  // DepthOnlyPushConstants
    Pipeline pipeline_;
    shader_interface::DepthOnlyPushConstants push_{};
    float drop_m_ = 0.0f;
};

}  // namespace gusuku::runtime_detail
