// The frame on the CPU (runtime_impl.h): the frame's light, then frame_preparation.h's pure functions, whose
// results go to each pass's prepare, in the order their inputs need: the ground quads and the shadow maps' fit
// (the sun), the uniforms (the fit), the colour match (the blend), the occluder (the uniforms), the camera (the
// colour match's grid).

#include <string>

#include "gusuku/formats/bakeset_validate.h"
#include "gusuku/maths/indirect_carry.h"
#include "runtime_camera.h"
#include "runtime_impl.h"

namespace gusuku::runtime_detail {

void RuntimeImpl::checkFrame(const FrameInput& frame) const {
    std::optional<std::string> problem = findFrameProblem(frame, options_.frame_width, options_.frame_height);
    if (!problem) problem = findCameraProblem(frame, options_);
    if (problem) throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "frame: " + *problem);
}

// The frame's checks come first (checkFrame), then the slot (acquireSlot), then this: the passes may write the
// slot's host-visible buffers, whose previous frame has completed.
// The sun-evidence pass's view: the frame's camera and slot blend with the clear sky's E_sun (sun_scale 1), against
// which the frame's lit ground measures the sun's strength now.
void RuntimeImpl::prepareSunEvidence(const FrameInput& frame, const SlotBlend& blend, bool measure) {
    GroundMatchView view;
    if (measure) {
        try {
            const SkyAndSun clear_sun{frame.weather.cloud_cover, 1.0f};
            const FrameLighting clear = computeFrameLighting(manifest_, frameObserverFor(frame, manifest_.site),
                                                             frame.utc_unix_seconds, clear_sun, frame.blend_slots);
            view = groundMatchViewFor(frame, clear, true, blend);
        } catch (const std::exception& error) {
            throw RuntimeError(RuntimeErrorCode::kInvalidFrame, std::string("frame: ") + error.what());
        }
    }
    sun_evidence_->prepare(submission_->slot(), measure, view, frame_set_->uniforms(), frame.utc_unix_seconds);
}

FrameInfo RuntimeImpl::prepareFrame(const FrameInput& frame) {
    FrameLighting lighting;
    try {
        const float cover = frame.weather.cloud_cover;
        const SkyAndSun sky_and_sun{cover, frame.weather.sun_scale < 0.0f ? 1.0f - cover : frame.weather.sun_scale};
        lighting = computeFrameLighting(manifest_, frameObserverFor(frame, manifest_.site), frame.utc_unix_seconds,
                                        sky_and_sun, frame.blend_slots);
        // Past the slots the sun's bounce fades with the sun instead of being held (indirect_carry.h).
        const SunBounceFit bounce = fitSunBounce(manifest_, scene_.slot_mean_indirect);
        lighting.sunny_weight *= float(indirectCarry(manifest_, bounce, lighting));
    } catch (const std::exception& error) {
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, std::string("frame: ") + error.what());
    }
    FrameInfo info = frameInfoFor(lighting);
    const uint32_t slot = submission_->slot();

    const FrameFlags flags = frameFlagsFor(frame.mode, lighting, scene_.occluder_index_count > 0);
    const glm::dvec3 shadow_sun = shadowSunDirectionFor(lighting.sun, options_.shadow_sun_step_deg);
    ground_->prepare(slot, {groundQuadsWanted(frame, flags), !flags.direct_only, flags.sun_shines, shadow_sun},
                     slotBlendFor(lighting), lighting.sun_irradiance_rgb);
    info.ground_quads_drawn = ground_->quadsDrawn();
    info.ground_quads_total = scene_.ground_quad_capacity;
    // The sun-evidence pass reads the site's map whenever the sun is up, also when the app hides the sun (sun_scale 0):
    // that is when it must see the sun come back.
    const bool evidence_possible = sun_evidence_ && lighting.sun.above_horizon && !flags.direct_only;
    shadows_->prepare(shadow_sun, flags.sun_shines, flags.site_shadows || evidence_possible);

    const SlotBlend blend = slotBlendFor(lighting);
    const FrameScene scene{scene_.scene_radius_m, scene_.irradiance_scale, scene_.slot_mean_indirect,
                           manifest_.ground_grid.grid};
    frame_set_->prepare(frameUniformsFor(frame, lighting, flags, blend, shadows_->fit(), options_, scene));
    colour_->prepare(frame, lighting, blend, flags.sun_shines);
    if (sun_evidence_)
        prepareSunEvidence(frame, blend, sun_evidence_enabled_ && evidence_possible && colour_->measuresGround());
    occluder_->prepare(frame_set_->uniforms());
    camera_->prepare(slot, frame, colour_->packGrid());
    return info;
}

}  // namespace gusuku::runtime_detail
