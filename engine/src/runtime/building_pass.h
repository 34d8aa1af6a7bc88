#pragma once
// The building in the main pass (docs/design.md 8): each material's run of indices with its base colour, the
// baked light and the sun's shadows of the frame set; the alpha-masked materials last, with their discard (or,
// multisampled, alpha to coverage). It marks its pixels in the stencil so the ground ratio leaves them alone.
// A FramePass (frame_pass.h). Private to gusuku_runtime.

#include "device_object.h"
#include "frame_pass.h"

namespace gusuku::runtime_detail {

class FrameSet;
class MaterialSets;

class BuildingPass final : public FramePass {
public:
    BuildingPass(const PassContext& context, const FrameSet& frame_set, const MaterialSets& materials,
                 VkRenderPass main_pass, VkSampleCountFlagBits samples);
    void recordInMainPass(PassRecording& recording) override;

private:
    const PassContext context_;
    const FrameSet& frame_set_;
    const MaterialSets& materials_;
    Pipeline pipeline_;
    Pipeline masked_pipeline_;  // only when the bake set has an alpha-masked material
};

}  // namespace gusuku::runtime_detail
