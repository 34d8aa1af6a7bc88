// The frame on the CPU as pure functions (see frame_preparation.h).

#include "frame_preparation.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

#include <glm/geometric.hpp>

#include "runtime_camera.h"

namespace gusuku::runtime_detail {
namespace {

using shader_interface::DepthOnlyPushConstants;
using shader_interface::FrameUniforms;

void toShader(const glm::dmat4& matrix, shader_interface::mat4& out) {
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 4; ++row) out.columns[column][row] = float(matrix[column][row]);
}

void toShader(const glm::dvec3& xyz, shader_interface::vec3& out) {
    out = {{float(xyz.x), float(xyz.y), float(xyz.z)}};
}

// The slots' layers and weights, and direct-only's ambient and darkening.
void writeSlots(const FrameLighting& lighting, const SlotBlend& blend, const RuntimeOptions& options,
                const FrameScene& scene, FrameUniforms& u) {
    const float slot_a = float(std::max(lighting.slot_a, 0)), slot_b = float(std::max(lighting.slot_b, 0));
    const float overcast = float(std::max(lighting.overcast_slot, 0));
    u.slot_layers = {{slot_a, slot_b, overcast}};
    u.slot_weights = {{blend.weights[0], blend.weights[1], blend.weights[2]}};
    u.irradiance_scale = scene.irradiance_scale;
    const glm::dvec3 ambient = blendedMeanIndirect(blend, scene.slot_mean_indirect);
    toShader(ambient * double(options.direct_only_ambient_fraction), u.direct_only_ambient);
    u.direct_only_shadow_darkening = options.direct_only_shadow_darkening;
}

// std140 puts each vec3 at a 16-byte offset with the scalar after it in its tail (interface_types.h).
static_assert(offsetof(FrameUniforms, shadow_map_x_enu) == 224 && offsetof(FrameUniforms, shadow_texel_m) == 236);
static_assert(offsetof(FrameUniforms, shadow_map_y_enu) == 240 && offsetof(FrameUniforms, shadow_texel_depth) == 252);

// The maps' constants from the matrix itself (orthographic with orthogonal rows, shadow_fit.h: |row x| = 2 /
// window side, |row z| = 1 / depth range), so they agree with what the shaders project with.
void writeShadow(const ShadowFit& fit, const RuntimeOptions& options, FrameUniforms& u) {
    toShader(fit.enu_to_clip, u.enu_to_shadow_clip);
    const glm::dmat4& m = fit.enu_to_clip;
    const glm::dvec3 row_x(m[0][0], m[1][0], m[2][0]), row_y(m[0][1], m[1][1], m[2][1]);
    const glm::dvec3 row_z(m[0][2], m[1][2], m[2][2]);
    const double texel_m = 2.0 / (double(options.shadow_map_size) * glm::length(row_x));
    toShader(glm::normalize(row_x), u.shadow_map_x_enu);
    toShader(glm::normalize(row_y), u.shadow_map_y_enu);
    u.shadow_texel_m = float(texel_m);
    u.shadow_texel_depth = float(texel_m * glm::length(row_z));
    u.shadow_texel_uv = 1.0f / float(options.shadow_map_size);
    u.shadow_depth_bias = float(shadowDepthBias(options.shadow_bias_texels, fit));
    u.shadow_pcf_radius = float(options.shadow_pcf_radius);
}

void writeGround(const GroundGrid& grid, FrameUniforms& u) {
    u.pass_through_threshold = kPassThroughThreshold;
    u.ground_origin_east_m = float(grid.origin_enu_m.x);
    u.ground_origin_north_m = float(grid.origin_enu_m.y);
    u.ground_cell_m = float(grid.cell_m);
    u.ground_pull_m = kGroundPullM;
    u.ground_columns = std::max(grid.columns, 1);
    u.ground_rows = std::max(grid.rows, 1);
}

}  // namespace

FrameFlags frameFlagsFor(RenderMode mode, const FrameLighting& lighting, bool has_occluder) {
    FrameFlags flags;
    flags.direct_only = mode == RenderMode::kDirectOnly;
    flags.sun_shines = lighting.sun.above_horizon && glm::length(lighting.sun_irradiance_rgb) > 0.0;
    flags.site_shadows = flags.sun_shines && !flags.direct_only && has_occluder;
    return flags;
}

SunObserver frameObserverFor(const FrameInput& frame, const BakeSetSite& site) {
    const GeoPosition position =
        frame.position.value_or(GeoPosition{site.latitude_deg, site.longitude_deg, site.height_m});
    SunObserver observer;
    observer.latitude_deg = position.latitude_deg;
    observer.longitude_deg = position.longitude_deg;
    observer.height_m = position.height_m;
    return observer;
}

FrameInfo frameInfoFor(const FrameLighting& lighting) {
    FrameInfo info;
    info.sun_azimuth_deg = lighting.sun.azimuth_deg;
    info.sun_apparent_elevation_deg = lighting.sun.apparent_elevation_deg;
    info.sun_above_horizon = lighting.sun.above_horizon;
    info.sun_direction_enu = lighting.sun.direction_enu;
    info.sun_irradiance_rgb = lighting.sun_irradiance_rgb;
    info.slot_a = lighting.slot_a;
    info.slot_b = lighting.slot_b;
    info.slot_b_weight = lighting.slot_b_weight;
    info.overcast_slot = lighting.overcast_slot;
    info.overcast_weight = lighting.overcast_weight;
    return info;
}

glm::dvec3 shadowSunDirectionFor(const SunPosition& sun, float step_deg) {
    if (!(step_deg > 0.0f)) return sun.direction_enu;
    const double step = double(step_deg);
    const double azimuth = std::round(sun.azimuth_deg / step) * step * std::numbers::pi / 180.0;
    const double elevation = std::round(sun.apparent_elevation_deg / step) * step * std::numbers::pi / 180.0;
    return glm::dvec3(std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth),
                      std::sin(elevation));
}

bool groundQuadsWanted(const FrameInput& frame, const FrameFlags& flags) {
    return flags.direct_only ? flags.sun_shines : frame.ground_ratio;
}

SlotBlend slotBlendFor(const FrameLighting& lighting) {
    SlotBlend blend;
    blend.slots[0] = lighting.slot_a;
    blend.slots[1] = lighting.slot_b;
    blend.slots[2] = lighting.overcast_slot;
    blend.weights[0] = lighting.slot_a >= 0 ? lighting.sunny_weight * (1.0f - lighting.slot_b_weight) : 0.0f;
    blend.weights[1] = lighting.slot_b >= 0 ? lighting.sunny_weight * lighting.slot_b_weight : 0.0f;
    blend.weights[2] = lighting.overcast_slot >= 0 ? lighting.overcast_weight : 0.0f;
    return blend;
}

glm::dvec3 blendedMeanIndirect(const SlotBlend& blend, std::span<const glm::vec3> slot_mean_indirect) {
    glm::dvec3 ambient(0.0);
    for (int index = 0; index < 3; ++index)
        if (blend.slots[index] >= 0)
            ambient += double(blend.weights[index]) * glm::dvec3(slot_mean_indirect[size_t(blend.slots[index])]);
    return ambient;
}

double cameraFarPlaneM(double scene_radius_m, const glm::dvec3& camera_position_enu) {
    return std::max(kFarPlaneSceneRadii * scene_radius_m + glm::length(camera_position_enu), kMinFarPlaneM);
}

double shadowDepthBias(float bias_texels, const ShadowFit& fit) {
    return bias_texels * fit.texel_size_m / fit.depth_range_m;
}

FrameUniforms frameUniformsFor(const FrameInput& frame, const FrameLighting& lighting, const FrameFlags& flags,
                               const SlotBlend& blend, const ShadowFit& fit, const RuntimeOptions& options,
                               const FrameScene& scene) {
    FrameUniforms u{};
    const double far_m = cameraFarPlaneM(scene.scene_radius_m, frame.pose.position_enu);
    toShader(cameraEnuToClip(frame.intrinsics, frame.pose, kNearPlaneM, far_m), u.enu_to_clip);
    toShader(frame.pose.position_enu, u.camera_position);
    u.exposure = frame.exposure;
    toShader(lighting.sun.direction_enu, u.sun_direction);
    u.sun_shines = flags.sun_shines ? 1u : 0u;
    toShader(lighting.sun_irradiance_rgb, u.sun_irradiance);
    u.site_shadows = flags.site_shadows ? 1u : 0u;
    u.render_mode = flags.direct_only ? RUNTIME_RENDER_MODE_DIRECT_ONLY : RUNTIME_RENDER_MODE_PROPOSED;
    writeSlots(lighting, blend, options, scene, u);
    writeShadow(fit, options, u);
    writeGround(scene.ground_grid, u);
    return u;
}

DepthOnlyPushConstants shadowPushFor(const ShadowFit& fit) {
    DepthOnlyPushConstants push{};
    toShader(fit.enu_to_clip, push.enu_to_clip);
    return push;
}

DepthOnlyPushConstants occluderPushFor(const FrameUniforms& uniforms) {
    DepthOnlyPushConstants push{};
    push.enu_to_clip = uniforms.enu_to_clip;
    push.pull_origin = uniforms.camera_position;
    push.pull_m = -kOccluderPushM;
    return push;
}

GroundMatchView groundMatchViewFor(const FrameInput& frame, const FrameLighting& lighting, bool sun_shines,
                                   const SlotBlend& blend) {
    GroundMatchView view;
    view.fx = frame.intrinsics.fx;
    view.fy = frame.intrinsics.fy;
    view.cx = frame.intrinsics.cx;
    view.cy = frame.intrinsics.cy;
    view.camera_position_enu = frame.pose.position_enu;
    view.camera_to_enu = frame.pose.camera_to_enu;
    view.sun_direction_enu = lighting.sun.direction_enu;
    view.sun_shines = sun_shines;
    view.sun_irradiance_rgb = lighting.sun_irradiance_rgb;
    view.exposure = frame.exposure;
    for (int index = 0; index < 3; ++index) {
        view.slots[index] = blend.slots[index];
        view.weights[index] = blend.weights[index];
    }
    return view;
}

ColourSource colourSourceFor(ColourMatchMode requested, bool direct_only, const SlotBlend& blend,
                             std::span<const LabStatistics> slot_statistics) {
    ColourSource source;
    source.mode = direct_only ? ColourMatchMode::kOff : requested;
    LabStatistics blended[3];
    for (int index = 0; index < 3; ++index)
        if (blend.slots[index] >= 0) blended[index] = slot_statistics[size_t(blend.slots[index])];
    if (blend.weights[0] + blend.weights[1] + blend.weights[2] > 0.0f)
        source.statistics = blendLabStatistics(blended, blend.weights);
    else
        source.mode = ColourMatchMode::kOff;  // night: nothing baked to match from
    return source;
}

}  // namespace gusuku::runtime_detail
