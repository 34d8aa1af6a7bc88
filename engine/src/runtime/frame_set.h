#pragma once
// The shading passes' frame set (docs/design.md 8): one descriptor set that the building and the ground ratio
// both read (this frame's uniforms, the two shadow maps, the lightmaps, the ground's irradiance and geometry, the
// colour match's state), their shared pipeline layout (the frame set, a material set, MaterialPushConstants),
// and the uniform block, written into its buffer in the frame's command buffer so that no host write lands under
// a frame still in flight. A FramePass (frame_pass.h): its recordBefore is that write. Private to gusuku_runtime.

#include "device_object.h"
#include "frame_pass.h"
#include "gusuku/gpu/gpu_compute.h"
#include "runtime_interface.h"

namespace gusuku::runtime_detail {

class MaterialSets;
class ShadowPass;

class FrameSet final : public FramePass {
public:
    /// colour_state: the colour match's state buffer (the statistics pass's, or a buffer of zeros: match off).
    FrameSet(const PassContext& context, const ShadowPass& shadows, const MaterialSets& materials,
             const GpuBuffer& colour_state);

    /// Host side: this frame's uniform block (frameUniformsFor).
    void prepare(const shader_interface::FrameUniforms& uniforms) { uniforms_ = uniforms; }
    const shader_interface::FrameUniforms& uniforms() const { return uniforms_; }
    void recordBefore(PassRecording& recording) override;

    /// The building's and the ground's pipeline layout.
    VkPipelineLayout shadingLayout() const { return shading_layout_.get(); }
    /// Binds the set unless this recording's command buffer has it bound already (PassRecording says why once
    /// only).
    void bindOnce(PassRecording& recording) const;
    uint64_t memoryBytes() const { return uniform_buffer_.size(); }

private:
    void createSamplers(const PassContext& context);
    void writeSet(const PassContext& context, const ShadowPass& shadows, const GpuBuffer& colour_state);

    Sampler linear_sampler_;        // lightmaps and ground images: bilinear on their one level
    Sampler shadow_sampler_;        // depth compare
    Sampler shadow_depth_sampler_;  // nearest, no compare: the building's map read as depths
    DescriptorSetLayout set_layout_;
    DescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;  // freed with the pool
    PipelineLayout shading_layout_;
    GpuBuffer uniform_buffer_;              // device-local FrameUniforms
    shader_interface::FrameUniforms uniforms_{};
};

}  // namespace gusuku::runtime_detail
