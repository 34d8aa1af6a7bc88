#version 450
// Camera kernel: a pinhole camera's view of the baked scene, for the sample site's camera frame and the
// benchmark's ground truth. One invocation per (pixel, sample): x indexes the pixel (y * width + x), y the
// sample within this dispatch's chunk; each writes its one-sample radiance to a scratch slot, and
// bake_accumulate.comp adds a chunk's samples onto the pixel sums in sample order, so a render is the same bits
// however it was split into chunks. One path per invocation for the reason bake_irradiance.comp gives
// (llvmpipe's loop limiter silently cuts long invocations short).
//
// The radiance along a camera ray: the sky map's (sun disc removed, as the bake removes it: the sun is seen
// only by next-event estimation, never twice) when it escapes; at a surface of albedo rho,
//     rho / pi * (E_sun + E_ind) + emission,
// E_sun by sunIrradianceAt and E_ind by estimateIndirectIrradiance: the bake's own estimators
// (irradiance_paths.glsl), so the truth and a bake agree by construction where they should. The back of a
// one-sided face of a closed part is black (the ray is inside a solid); an open one-sided face (a cut-out card)
// is lit on both sides, as Cycles and the runtime draw it. The sample position inside the pixel is the path's
// first 2D Sobol draw (anti-aliasing by stratified jitter).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require

#include "camera_trace_interface.h"
#include "constants.glsl"

layout(local_size_x = CAMERA_TRACE_WORKGROUP_SIZE) in;

#define BVH_NODE_BINDING CAMERA_BVH_NODE_BINDING
#define BVH_TRIANGLE_BINDING CAMERA_BVH_TRIANGLE_BINDING
#define SHADING_TRIANGLE_BINDING CAMERA_SHADING_TRIANGLE_BINDING
#define MATERIAL_BINDING CAMERA_MATERIAL_BINDING
#define TEXTURE_BINDING CAMERA_TEXTURE_BINDING
#define SKY_RADIANCE_BINDING CAMERA_SKY_RADIANCE_BINDING
#define SKY_TABLE_BINDING CAMERA_SKY_TABLE_BINDING

#include "sampling.glsl"
#include "bvh_traverse.glsl"
#include "scene_shading.glsl"
#include "sky_sampling.glsl"
#include "irradiance_paths.glsl"

layout(std430, set = 0, binding = CAMERA_SAMPLE_ESTIMATE_BINDING) writeonly buffer SampleEstimates { vec4 sample_estimates[]; };
layout(std430, set = 0, binding = CAMERA_GUIDE_BINDING) writeonly buffer Guides { vec4 guides[]; };
layout(std430, set = 0, binding = CAMERA_RAY_COUNTER_BINDING) buffer RayCounter { uint rays_traced_total[]; };

// The push-constant block `pc` (CameraTracePushConstants) is declared in camera_trace_interface.h.

// Unit ENU direction of the ray through image point (u, v) (pixels, (0, 0) the top-left corner): the camera-frame
// direction ((u - cx) / fx, (v - cy) / fy, 1), which projects back to (u, v) by u = fx X / Z + cx.
vec3 cameraRayDirection(vec2 image_point) {
    vec3 camera = vec3((image_point.x - pc.intrinsics.z) / pc.intrinsics.x,
                       (image_point.y - pc.intrinsics.w) / pc.intrinsics.y, 1.0);
    return normalize(vec3(dot(pc.camera_row0.xyz, camera), dot(pc.camera_row1.xyz, camera),
                          dot(pc.camera_row2.xyz, camera)));
}

void main() {
    uint pixel_index = gl_GlobalInvocationID.x;
    uint sample_in_chunk = gl_GlobalInvocationID.y;
    bool guide_pass = (pc.flags & CAMERA_FLAG_GUIDE_PASS) != 0u;
    bool in_range = pixel_index < pc.width * pc.height && sample_in_chunk < pc.sample_count;
    if (in_range) {
        PathSettings settings;
        settings.max_bounces = pc.max_bounces;
        settings.skip_flags = pc.skip_flags;
        settings.sun_present = (pc.flags & CAMERA_FLAG_SUN_PRESENT) != 0u;
        settings.sun_direction = pc.sun_direction_cos_max.xyz;
        settings.sun_cos_max = pc.sun_direction_cos_max.w;
        settings.sun_irradiance = pc.sun_irradiance_ray_offset.xyz;
        settings.ray_offset = pc.sun_irradiance_ray_offset.w;
        settings.sky_next_event = (pc.flags & CAMERA_FLAG_SKY_NEXT_EVENT) != 0u;

        Rng rng = rngForSample(pc.seed, pixel_index, pc.first_sample + sample_in_chunk);
        vec2 pixel_corner = vec2(float(pixel_index % pc.width), float(pixel_index / pc.width));
        vec2 in_pixel = guide_pass ? vec2(0.5) : rngNext2(rng);
        vec3 origin = vec3(pc.camera_row0.w, pc.camera_row1.w, pc.camera_row2.w);
        vec3 direction = cameraRayDirection(pixel_corner + in_pixel);

        BvhHit hit;
        g_rays_traced++;
        bool surface_hit = bvhTraceClosest(origin, direction, 1e30, settings.skip_flags, hit);
        SurfacePoint surface;
        bool lit_side = false;
        if (surface_hit) {
            surface = evaluateSurface(hit.triangle_index, hit.barycentric_u, hit.barycentric_v, direction);
            // Only a closed part's one-sided back is dark (the inside of a solid); an open one-sided face is a
            // sheet lit on both sides (irradiance_paths.glsl).
            lit_side = surface.front_face || surface.double_sided || !surface.closed_part;
        }

        if (guide_pass) {
            uint base = pixel_index * CAMERA_GUIDE_VEC4S_PER_PIXEL;
            guides[base + 0u] = surface_hit ? vec4(surface.shading_normal, hit.t) : vec4(0.0, 0.0, 0.0, -1.0);
            guides[base + 1u] = lit_side ? vec4(surface.albedo, 1.0) : vec4(0.0);
            // The sun's share, averaged over a 2 x 2 grid in the pixel (each sub-ray's own first hit), so a
            // pixel that a shadow's edge crosses reads in between and the denoiser mixes it with neither side.
            float sun_share = 0.0;
            if (settings.sun_present) {
                for (uint corner = 0u; corner < 4u; ++corner) {
                    vec2 at = pixel_corner + vec2(0.25 + 0.5 * float(corner & 1u), 0.25 + 0.5 * float(corner >> 1u));
                    vec3 sub_direction = cameraRayDirection(at);
                    BvhHit sub_hit;
                    g_rays_traced++;
                    if (!bvhTraceClosest(origin, sub_direction, 1e30, settings.skip_flags, sub_hit)) continue;
                    SurfacePoint sub = evaluateSurface(sub_hit.triangle_index, sub_hit.barycentric_u,
                                                       sub_hit.barycentric_v, sub_direction);
                    float cos_sun = dot(sub.shading_normal, settings.sun_direction);
                    if (!(sub.front_face || sub.double_sided || !sub.closed_part) || cos_sun <= 0.0 ||
                        dot(sub.geometric_normal, settings.sun_direction) <= 0.0)
                        continue;
                    vec3 position = origin + sub_direction * sub_hit.t + sub.geometric_normal * settings.ray_offset;
                    if (!traceOccluded(position + sub.shading_normal * settings.ray_offset, settings.sun_direction,
                                       settings))
                        sun_share += 0.25 * cos_sun;
                }
            }
            guides[base + 2u] = lit_side ? vec4(surface.emission, sun_share) : vec4(0.0);
        } else {
            vec3 radiance = vec3(0.0);
            if (!surface_hit) {
                radiance = skyRadiance(direction);
            } else if (lit_side) {
                // Leave the surface on the side the ray came from, as the paths do at each vertex.
                vec3 position = origin + direction * hit.t + surface.geometric_normal * settings.ray_offset;
                // The path vertex's convention (irradiance_paths.glsl): the shading normal's cosine lobe, clipped
                // at the face plane on the side the ray came from.
                vec3 irradiance = sunIrradianceAt(position, surface.shading_normal, surface.geometric_normal, rng,
                                                  settings);
                float backface_score;
                irradiance += estimateIndirectIrradiance(position, surface.shading_normal, surface.geometric_normal,
                                                         rng, settings, backface_score);
                radiance = surface.albedo / kPi * irradiance + surface.emission;
            }
            // A NaN from a degenerate input must never reach an output: drop that sample's value.
            if (any(isnan(radiance)) || any(isinf(radiance))) radiance = vec3(0.0);
            sample_estimates[sample_in_chunk * (pc.width * pc.height) + pixel_index] = vec4(radiance, 1.0);
        }
    }
    // One atomic per subgroup rather than per invocation.
    uint subgroup_rays = subgroupAdd(in_range ? g_rays_traced : 0u);
    if (subgroupElect()) atomicAdd(rays_traced_total[0], subgroup_rays);
}
