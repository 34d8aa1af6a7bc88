#pragma once
// The frame on the CPU (docs/design.md 8): pure functions from a frame's input, its light and the bake set's
// static description to what the frame's passes read: the uniform block, the depth passes' push constants, the
// colour match's source and view. No Vulkan calls and no state: RuntimeImpl::prepareFrame (runtime_frame.cpp)
// keeps what they return and uploads it; tests/test_frame_preparation.cpp checks them without a GPU. The ground
// quads a frame draws are chosen by ground_quads.h. Private to gusuku_runtime.

#include <optional>
#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "gusuku/formats/bakeset_manifest.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/colour_match.h"
#include "gusuku/maths/frame_lighting.h"
#include "gusuku/formats/ground_grid.h"
#include "gusuku/maths/shadow_fit.h"
#include "gusuku/maths/sun.h"
#include "gusuku/runtime/runtime.h"
#include "runtime_depth_push.h"
#include "runtime_interface.h"

namespace gusuku::runtime_detail {

/// The camera's near plane: close enough for a phone held up to a wall, far enough to keep depth precision.
constexpr double kNearPlaneM = 0.05;
/// The far plane lies beyond everything: the camera's distance from the ENU origin (the site's reference point,
/// in or beside the scene) plus this many scene radii, a generous margin for the far side of the scene...
constexpr double kFarPlaneSceneRadii = 4.0;
/// ... and never nearer than this, so a tiny scene still gets a usable depth range.
constexpr double kMinFarPlaneM = 100.0;
/// The ground pass moves towards the camera by this, so the occluder mesh it was sampled from does not hide it.
constexpr float kGroundPullM = 0.10f;
/// The occluder pass moves away from the camera by this, for the same reason from the other side.
constexpr float kOccluderPushM = 0.05f;
/// |ratio - 1| below this in every channel: the camera pixel is left untouched (half an 8-bit step).
constexpr float kPassThroughThreshold = 0.5f / 255.0f;

/// What the frame's mode and light switch on.
struct FrameFlags {
    bool direct_only = false;   ///< RenderMode::kDirectOnly
    bool sun_shines = false;    ///< the sun is above the horizon with E_sun > 0
    bool site_shadows = false;  ///< the site's occluder casts the sun's shadow (proposed mode, an occluder, sun)
};
FrameFlags frameFlagsFor(RenderMode mode, const FrameLighting& lighting, bool has_occluder);

/// The observer the sun is computed for: the frame's position, or the bake set's site when it has none.
SunObserver frameObserverFor(const FrameInput& frame, const BakeSetSite& site);

/// The frame's report of its sun and slots (the ground quads' counts are the caller's to fill).
FrameInfo frameInfoFor(const FrameLighting& lighting);

/// The shadow maps' sun: the sun's azimuth and apparent elevation rounded to multiples of step_deg, so that the
/// maps are re-rendered only every step of its motion; step_deg <= 0: the sun's own direction.
glm::dvec3 shadowSunDirectionFor(const SunPosition& sun, float step_deg);

/// Whether the frame draws ground quads at all: direct-only mode darkens the building's shadow whenever the sun
/// shines; proposed mode draws the ratio when the frame asks for it.
bool groundQuadsWanted(const FrameInput& frame, const FrameFlags& flags);

/// The frame's blend of baked slots, per term (sunny A, sunny B, overcast): the manifest slot (-1: none) and its
/// weight (0 for a missing slot). The weights include cloud cover and the twilight fade.
struct SlotBlend {
    int slots[3] = {-1, -1, -1};
    float weights[3] = {0.0f, 0.0f, 0.0f};
};
SlotBlend slotBlendFor(const FrameLighting& lighting);

/// Direct-only mode's ambient before RuntimeOptions::direct_only_ambient_fraction: the blend's weighted sum of
/// each slot's mean baked E_ind over the building.
glm::dvec3 blendedMeanIndirect(const SlotBlend& blend, std::span<const glm::vec3> slot_mean_indirect);

/// The camera's far plane for a camera at camera_position_enu (see kFarPlaneSceneRadii).
double cameraFarPlaneM(double scene_radius_m, const glm::dvec3& camera_position_enu);

/// The depth bias of the shadow lookup: RuntimeOptions::shadow_bias_texels texels of the map, in its depth units.
double shadowDepthBias(float bias_texels, const ShadowFit& fit);

/// The bake set's static description that the uniforms carry.
struct FrameScene {
    double scene_radius_m = 1.0;                    ///< GpuScene::scene_radius_m
    float irradiance_scale = 1.0f;                  ///< GpuScene::irradiance_scale
    std::span<const glm::vec3> slot_mean_indirect;  ///< GpuScene::slot_mean_indirect, per slot
    GroundGrid ground_grid;                         ///< the manifest's
};

/// The frame's uniform block (runtime_interface.h).
shader_interface::FrameUniforms frameUniformsFor(const FrameInput& frame, const FrameLighting& lighting,
                                                 const FrameFlags& flags, const SlotBlend& blend,
                                                 const ShadowFit& fit, const RuntimeOptions& options,
                                                 const FrameScene& scene);

/// Both shadow maps' push constants: the sun's view of the fit, no pull.
shader_interface::DepthOnlyPushConstants shadowPushFor(const ShadowFit& fit);
/// The occluder's push constants: the camera's view, pushed kOccluderPushM away from the camera.
shader_interface::DepthOnlyPushConstants occluderPushFor(const shader_interface::FrameUniforms& uniforms);

/// Mode kGround's view of the frame: its camera, its sun and its blend.
GroundMatchView groundMatchViewFor(const FrameInput& frame, const FrameLighting& lighting, bool sun_shines,
                                   const SlotBlend& blend);

/// The colour match this frame runs and its source, the baked appearance's statistics blended like the
/// lightmaps. Direct-only mode runs none; nor does a frame with no baked light to match from (night), whose
/// statistics are then nothing (the caller keeps its last ones).
struct ColourSource {
    ColourMatchMode mode = ColourMatchMode::kOff;
    std::optional<LabStatistics> statistics;
};
ColourSource colourSourceFor(ColourMatchMode requested, bool direct_only, const SlotBlend& blend,
                             std::span<const LabStatistics> slot_statistics);

}  // namespace gusuku::runtime_detail
