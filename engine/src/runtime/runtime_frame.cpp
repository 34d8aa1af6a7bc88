// The frame on the CPU (runtime_impl.h): the frame's light, then frame_preparation.h's and ground_quads.h's pure
// functions, whose results the runtime keeps (the shadow maps' fit and validity, the ground quads chosen, the
// colour match's source) and uploads (the uniforms, the chosen quads, the camera frame).

#include <string>

#include "ground_quads.h"
#include "gusuku/formats/bakeset_validate.h"
#include "runtime_camera.h"
#include "runtime_impl.h"

namespace gusuku::runtime_detail {

void RuntimeImpl::checkFrame(const FrameInput& frame) const {
    std::optional<std::string> problem = findFrameProblem(frame, options_.frame_width, options_.frame_height);
    if (!problem) problem = findCameraProblem(frame, options_);
    if (problem) throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "frame: " + *problem);
}

// The frame's checks come first (checkFrame), then the slot (acquireSlot), then this: everything below may
// write the slot's host-visible buffers, whose previous frame has completed.
FrameInfo RuntimeImpl::prepareFrame(const FrameInput& frame) {
    FrameLighting lighting;
    try {
        lighting = computeFrameLighting(manifest_, frameObserverFor(frame, manifest_.site), frame.utc_unix_seconds,
                                        frame.weather.cloud_cover, frame.blend_slots);
    } catch (const std::exception& error) {
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, std::string("frame: ") + error.what());
    }
    FrameInfo info = frameInfoFor(lighting);

    const FrameFlags flags = frameFlagsFor(frame.mode, lighting, scene_.occluder_index_count > 0);
    sun_shines_ = flags.sun_shines;
    site_shadows_ = flags.site_shadows;
    const glm::dvec3 shadow_sun = shadowSunDirectionFor(lighting.sun, options_.shadow_sun_step_deg);
    updateGroundSelection(groundQuadsWanted(frame, flags), !flags.direct_only, shadow_sun);
    info.ground_quads_drawn = ground_index_count_ / 6;
    info.ground_quads_total = scene_.ground_quad_capacity;
    updateShadowState(shadow_sun);

    const SlotBlend blend = slotBlendFor(lighting);
    const FrameScene scene{scene_.scene_radius_m, scene_.irradiance_scale, scene_.slot_mean_indirect,
                           manifest_.ground_grid.grid};
    uniforms_ = frameUniformsFor(frame, lighting, flags, blend, shadow_fit_, options_, scene);  // recordFrameStart
    prepareColourMatch(frame, lighting, blend);
    shadow_push_ = shadowPushFor(shadow_fit_);
    occluder_push_ = occluderPushFor(uniforms_);
    uploadGroundSelection(slots_[slot_]);
    camera_->prepare(slot_, frame);
    return info;
}

// The shadow maps' fit depends only on the static bounds and the rounded sun: made again, and the maps marked
// for re-rendering, only when that sun moves a step.
void RuntimeImpl::updateShadowState(const glm::dvec3& shadow_sun) {
    if (shadow_sun != shadow_sun_direction_) {
        shadow_sun_direction_ = shadow_sun;
        building_shadow_valid_ = site_shadow_valid_ = false;
        shadow_fit_ = fitShadowMap(scene_.receivers_min, scene_.receivers_max, scene_.casters_min,
                                   scene_.casters_max, shadow_sun, options_.shadow_map_size);
    }
    render_building_shadow_ = sun_shines_ && !building_shadow_valid_;
    render_site_shadow_ = site_shadows_ && !site_shadow_valid_;
}

// The ground quads to draw: chosen again only when what chooses them changes (the rounded sun, the mode, whether
// the sun shines); their margin covers the rounding. Each slot copies the newest choice into its own buffers
// (uploadGroundSelection) when it next renders, so no write lands under a frame still in flight.
void RuntimeImpl::updateGroundSelection(bool wanted, bool include_baked_changes, const glm::dvec3& shadow_sun) {
    const GroundSelectionKey key{wanted, include_baked_changes, sun_shines_, shadow_sun};
    if (ground_selection_key_ != key) {
        ground_selection_key_ = key;
        ground_index_count_ = ground_shadow_index_count_ = 0;
        if (wanted) {
            const GroundCells cells{manifest_.ground_grid.grid, scene_.ground_cell_state, scene_.ground_cell_height};
            const GroundQuadSelection selection =
                selectGroundQuads(cells, scene_.building_min, scene_.building_max, include_baked_changes,
                                  sun_shines_, shadow_sun, ground_cell_marked_, ground_shadow_candidate_,
                                  ground_quad_indices_);
            ground_index_count_ = selection.index_count;
            ground_shadow_index_count_ = selection.shadow_index_count;
        }
        ++ground_generation_;
    }
    draw_ground_ = ground_index_count_ > 0;
}

// The chosen quads into the slot's host-visible index buffer and their cells' shadow flags into its vertex
// stream, when the slot holds an older choice.
void RuntimeImpl::uploadGroundSelection(FrameSlot& slot) {
    if (slot.ground_generation == ground_generation_) return;
    slot.ground_generation = ground_generation_;
    if (ground_index_count_ == 0) return;
    slot.ground_indices.upload(ground_quad_indices_.data(), ground_index_count_ * sizeof(uint32_t));
    slot.ground_candidates.upload(ground_shadow_candidate_.data(), ground_shadow_candidate_.size() * sizeof(float));
}

// The colour match's mode and source this frame, and mode kGround's view; kAuto resolved (kGround where the bake
// set and the device allow it, else kOff: a default never makes a frame fail); whether the frame measures the
// camera (one in kColourStatisticsInterval, the first of a mode, the first after a reset).
void RuntimeImpl::prepareColourMatch(const FrameInput& frame, const FrameLighting& lighting, const SlotBlend& blend) {
    ColourMatchMode requested = frame.colour_match;
    if (requested == ColourMatchMode::kAuto)
        requested = statistics_ && statistics_->hasGround() ? ColourMatchMode::kGround : ColourMatchMode::kOff;
    if (requested != ColourMatchMode::kOff && !statistics_)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "frame: colour_match: needs subgroup arithmetic in compute shaders (a Vulkan 1.1 instance "
                           "and device), which this device lacks: use colour_match off");
    if (requested == ColourMatchMode::kGround && !statistics_->hasGround())
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "frame: colour_match: ground needs the bake set's ground_grid.albedo, which this bake set "
                           "lacks (bake it again)");
    const ColourSource source =
        colourSourceFor(requested, frame.mode == RenderMode::kDirectOnly, blend, slot_colour_statistics_);
    if (source.mode == ColourMatchMode::kGround)
        frame_ground_view_ = groundMatchViewFor(frame, lighting, sun_shines_, blend);
    if (source.statistics) frame_source_statistics_ = *source.statistics;
    if (source.mode != frame_colour_mode_) frames_to_next_measurement_ = 0;
    frame_colour_mode_ = source.mode;
    frame_measures_colour_ = source.mode != ColourMatchMode::kOff && frames_to_next_measurement_ == 0;
    if (frame_measures_colour_) frames_to_next_measurement_ = kColourStatisticsInterval - 1;
    else if (frames_to_next_measurement_ > 0) --frames_to_next_measurement_;
}

}  // namespace gusuku::runtime_detail
