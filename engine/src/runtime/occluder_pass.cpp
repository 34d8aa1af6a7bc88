// The site occluder's depth (occluder_pass.h).

#include "occluder_pass.h"

#include "depth_only_vert_spv.h"
#include "frame_preparation.h"
#include "runtime_pipelines.h"
#include "runtime_scene.h"

namespace gusuku::runtime_detail {

OccluderPass::OccluderPass(const PassContext& context, VkRenderPass main_pass, VkSampleCountFlagBits samples,
                           float drop_m)
    : context_(context), drop_m_(drop_m) {
    const VkDevice device = context.gpu.device;
    layout_ = createPipelineLayout(device, {}, VK_SHADER_STAGE_VERTEX_BIT,
                                   sizeof(shader_interface::DepthOnlyPushConstants));
    GraphicsPipelineDescription occluder;
    occluder.layout = layout_.get();
    occluder.render_pass = main_pass;
    occluder.samples = samples;  // every main-pass pipeline rasterises at the pass's sample count
    occluder.vertex_spirv = kDepthOnlyVertSpirv;
    occluder.vertex_spirv_bytes = sizeof(kDepthOnlyVertSpirv);
    occluder.vertex_input.stride = sizeof(float) * 3;  // bare vec3s
    occluder.vertex_input.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}};
    occluder.blend = BlendMode::kNoColourWrites;
    pipeline_ = Pipeline(device, createGraphicsPipeline(device, occluder));
}

void OccluderPass::prepare(const shader_interface::FrameUniforms& uniforms) {
    push_ = occluderPushFor(uniforms);
    push_.drop_m = drop_m_;
}

void OccluderPass::recordInMainPass(PassRecording& recording) {
    const GpuScene& scene = context_.scene;
    if (scene.occluder_index_count == 0) return;
    const VkCommandBuffer cmd = recording.cmd;
    const VkDeviceSize offset = 0;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_.get());
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof push_, &push_);
    const VkBuffer vertex_buffer = scene.occluder_vertices.handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
    vkCmdBindIndexBuffer(cmd, scene.occluder_indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, scene.occluder_index_count, 1, 0, 0, 0);
}

}  // namespace gusuku::runtime_detail
