#pragma once
// The sun's two shadow maps (docs/design.md 8): the building's (its opaque materials in one draw, the
// alpha-masked ones with their alpha test) and the site occluder's, each a depth-only pass of its own before the
// main pass. Both hold the sun's direction rounded to RuntimeOptions::shadow_sun_step_deg and are rendered again
// only when that rounded direction moves (the building and the site are static) or the app invalidates them.
// A FramePass (frame_pass.h). Private to gusuku_runtime.

#include <glm/vec3.hpp>

#include "device_object.h"
#include "frame_pass.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_image.h"
#include "gusuku/maths/shadow_fit.h"
#include "runtime_depth_push.h"

namespace gusuku::runtime_detail {

class MaterialSets;

class ShadowPass final : public FramePass {
public:
    /// The maps (left in SHADER_READ_ONLY_OPTIMAL, cleared, for frames that skip them), their pass and pipelines.
    /// occluder_drop_m: how far the occluder is lowered in the site's map, as in the camera's occluder pass (its
    /// simplification error: docs/design.md 3, "The building's foot").
    ShadowPass(const PassContext& context, const MaterialSets& materials, float occluder_drop_m = 0.0f);

    /// Host side: the fit of the maps to the sun rounded (shadowSunDirectionFor), made again when it moved; which
    /// maps this frame renders (the building's when the sun shines, the site's when the site casts shadows).
    void prepare(const glm::dvec3& shadow_sun, bool sun_shines, bool site_shadows);
    void recordBefore(PassRecording& recording) override;
    /// The next frame renders both maps again (Runtime::invalidateShadowMaps).
    void invalidate() { building_.valid = site_.valid = false; }

    const ShadowFit& fit() const { return fit_; }
    const GpuImage& buildingMap() const { return building_.image; }
    const GpuImage& siteMap() const { return site_.image; }
    uint64_t memoryBytes() const { return building_.image.memoryBytes() + site_.image.memoryBytes(); }

private:
    struct ShadowMap {
        GpuImage image;
        Framebuffer framebuffer;
        bool valid = false;   // holds the current fit's depths
        bool render = false;  // this frame renders it
    };
    struct Caster {
        VkPipeline pipeline;
        const GpuBuffer& vertices;
        const GpuBuffer& indices;
        uint32_t index_count;
        float drop_m = 0.0f;  // DepthOnlyPushConstants::drop_m
    };
    void createPipelines();
    void beginMap(VkCommandBuffer cmd, const ShadowMap& map, const Caster& caster) const;
    void recordMaskedMaterials(VkCommandBuffer cmd) const;

    const PassContext context_;
    const MaterialSets& materials_;
    const float occluder_drop_m_;
    RenderPass render_pass_;
    ShadowMap building_, site_;
    PipelineLayout depth_layout_;         // DepthOnlyPushConstants
    PipelineLayout masked_layout_;        // the material set, MaskedDepthPushConstants
    Pipeline building_pipeline_;          // the building's opaque materials
    Pipeline site_pipeline_;              // the occluder (bare vec3 vertices: a stride of its own)
    Pipeline masked_pipeline_;            // alpha-masked materials (depth_masked.frag), only when there are some
    glm::dvec3 sun_direction_{0.0};       // the rounded sun the fit is for
    ShadowFit fit_;
    shader_interface::DepthOnlyPushConstants push_{};  // both maps: the sun's view of the fit
};

}  // namespace gusuku::runtime_detail
