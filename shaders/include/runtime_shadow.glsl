// The runtime's shadow lookups. Needs FrameUniforms; the includer declares the building map's two samplers:
// `building_shadow` (sampler2DShadow, bilinear compare) and `building_shadow_depths` (sampler2D, nearest).
//   - The building's shadow (buildingSunVisibility, at the point shadowLookup placed): V in [0, 1] (1 lit) with the penumbra the sun's real disc
//     casts (angular radius 0.2675 degrees: 2 d tan of it wide at d metres from the caster), in three steps:
//       1. blocker search, fixed taps (no noise from frame to frame, bounded cost): the 4 x 4 texels about the
//          point and four 2 x 2 blocks on a ring (2 + shadow_pcf_radius) texels out, 8 gathers of the stored
//          depths. A texel blocks when it lies in front of the receiver's plane at its centre (the plane's own
//          depth change across the taps would shade a sloped receiver by itself) and in front of the point by a
//          texel's depth per texel it lies beside the point (blockerSums: not a floor beside a lit wall's
//          foot). None of the 4 x 4 blocks: lit, where most fragments stop after 4 gathers;
//       2. the blockers' mean distance d gives the penumbra's radius, d tan(0.2675 deg) over the texel's side
//          (the receiver is moved one texel x sin(normal, sun) along its normal first, so that its own plane
//          never blocks within the hardware's 2 x 2 footprint);
//       3. radius above kContactTexels: kDiscTaps bilinear compare taps on a Vogel disc of that radius, each
//          against the receiver's plane at the tap. Below it (a contact shadow: ribs, sills, a wall's foot, the
//          sun's penumbra narrower than the filter can draw), the one bilinear compare tap of the site's
//          slope-scaled bias, the sharpest the map can give; measured on the ribbed roof (tests/
//          test_runtime_shadows.cpp) it keeps the battens' shadows (-0.33 % from the truth; the 3 x 3 PCF it
//          replaces -1.02 %), and a receiver-plane test there darkened lit walls' feet on grazing floors.
//   - The site's shadow (shadowLookup): one compare tap with a slope-scaled depth bias (its edges come from far
//     away and are soft in the camera image anyway).
#ifndef GUSUKU_RUNTIME_SHADOW_GLSL
#define GUSUKU_RUNTIME_SHADOW_GLSL

// tan(the sun's mean apparent angular radius, 0.2675 degrees): the penumbra's half-width per metre from the caster.
const float kSunRadiusTangent = 0.0046688;
// The normal offset, in texels at sin(normal, sun) = 1 (step 1).
const float kNormalOffsetTexels = 1.0;
// A depth margin for what the plane does not know (float rounding, smoothly shaded normals), in texels' side.
const float kPlaneMarginTexels = 0.1;
// A blocker beside the point's ray must be nearer the sun by this many texels' side per texel it lies beside it
// (blockerSums): 1, a 45-degree cone about the ray.
const float kConcaveGuardSlope = 1.0;
// The blocker search's ring lies this many texels out plus shadow_pcf_radius (3 at the default 1) ...
const float kRingTexels = 2.0;
// ... and a penumbra radius up to this is a contact shadow: one bilinear compare tap with the site's slope-scaled
// bias. Its 10-90 % width, 1.1 texels, is the sun's disc's (1.37 radii) at this radius, so the step is smooth.
const float kContactTexels = 0.8;
const int kDiscTaps = 12;

#include "runtime_shadow_coordinates.glsl"

// The point's shadow-map coordinates and biased depth for the site's map; false outside the fitted window
// (nothing of the building can shade it there).
bool shadowLookup(vec3 position_enu, vec3 normal_enu, out vec2 uv, out float depth) {
    vec3 coordinates = siteShadowCoordinates(position_enu, normal_enu);
    uv = coordinates.xy;
    depth = coordinates.z;
    return insideShadowWindow(uv);
}

// The receiver as the building's map sees it, from the frame's constants (FrameUniforms: the maps' axes, texel
// side and texel depth, computed once on the CPU rather than from the matrix in every fragment).
struct ShadowReceiver {
    vec2 texel;           // position in texels (texel i's centre at i + 0.5)
    float depth;          // the offset point's map depth, less the margin
    vec2 plane_gradient;  // the receiver plane's map depth per texel step in x and y
};

// `cosine`: n . s held to kShadowMinCosine (shadowLookup's).
bool shadowReceiver(vec3 position_enu, vec3 normal_enu, float cosine, out ShadowReceiver receiver) {
    float sine = sqrt(1.0 - cosine * cosine);
    vec3 offset_enu = position_enu + normal_enu * (kNormalOffsetTexels * frame.shadow_texel_m * sine);
    vec4 clip = frame.enu_to_shadow_clip * vec4(offset_enu, 1.0);
    vec2 uv = clip.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
    receiver.texel = uv / frame.shadow_texel_uv;
    receiver.depth = clip.z - kPlaneMarginTexels * frame.shadow_texel_depth;
    // Along the plane, a step of one texel in map x moves the depth by -(n.x / n.z) texel_m (n in the map's
    // unit axes, n.z = -cosine towards the sun), held to the same grazing limit as the site's bias.
    vec2 slope = vec2(dot(frame.shadow_map_x_enu, normal_enu), dot(frame.shadow_map_y_enu, normal_enu)) / cosine;
    float steepest = length(slope);
    if (steepest > kShadowMaxBiasTangent) slope *= kShadowMaxBiasTangent / steepest;
    receiver.plane_gradient = slope * frame.shadow_texel_depth;
    return true;
}

// The 2 x 2 texels whose shared corner is `corner` (in texels), their depths `stored` (textureGather's order:
// (0, 1), (1, 1), (1, 0), (0, 0) from the block's first texel): the summed distance in front of the point (x) and
// the count (y) of those that block. A texel blocks when it lies in front of the receiver's plane at its centre,
// and in front of the point's own depth by kConcaveGuardSlope texels' depth per texel it lies beside the point:
// the plane alone would let a surface at a concave corner block (the ground's plane runs on under a sunlit
// wall's foot, the roof's under a batten's sunlit side), though it lies beside the point's ray, not on it; what
// does lie on the ray is nearer the sun than the point by more than this the farther it is from it. Four texels
// at once, without branches (a fragment's lanes do not diverge).
vec2 blockerSums(ShadowReceiver receiver, vec2 corner, vec4 stored) {
    vec2 first = corner - receiver.texel;
    vec4 offset_x = first.x + vec4(-0.5, 0.5, 0.5, -0.5);
    vec4 offset_y = first.y + vec4(0.5, 0.5, -0.5, -0.5);
    vec4 plane_depth = receiver.depth + receiver.plane_gradient.x * offset_x + receiver.plane_gradient.y * offset_y;
    vec4 lateral = sqrt(offset_x * offset_x + offset_y * offset_y);
    vec4 limit = min(plane_depth, receiver.depth - lateral * (kConcaveGuardSlope * frame.shadow_texel_depth));
    vec4 blocks = vec4(lessThan(stored, limit));
    return vec2(dot(blocks, receiver.depth - stored), dot(blocks, vec4(1.0)));
}

// The 2 x 2 block about `corner`: its blockers' sums.
vec2 blockSums(ShadowReceiver receiver, vec2 corner) {
    return blockerSums(receiver, corner, textureGather(building_shadow_depths, corner * frame.shadow_texel_uv, 0));
}

// The Vogel disc of kDiscTaps taps on the unit disc (tap i at radius sqrt((i + 0.5) / kDiscTaps), angle i times
// the golden angle), worked out once here rather than with a sqrt, a cos and a sin per tap and fragment:
// x, y and the radius.
const vec3 kDiscTapsUnit[kDiscTaps] = vec3[](
    vec3(0.2041241, 0.0000000, 0.2041241), vec3(-0.2606993, 0.2388219, 0.3535534),
    vec3(0.0399042, -0.4546878, 0.4564355), vec3(0.3285945, 0.4285934, 0.5400617),
    vec3(-0.6030114, -0.1066642, 0.6123724), vec3(0.5712250, -0.3633666, 0.6770032),
    vec3(-0.1910636, 0.7107470, 0.7359801), vec3(-0.3643790, -0.7015896, 0.7905694),
    vec3(0.7905567, 0.2887100, 0.8416254), vec3(-0.8224425, 0.3394923, 0.8897565),
    vec3(0.3964716, -0.8472368, 0.9354143), vec3(0.2929824, 0.9340742, 0.9789450));

// The wide penumbra: bilinear compare taps on a disc of `radius` texels, each against the plane at the tap less
// the plane's depth change across the hardware's 2 x 2 footprint.
float discVisibility(ShadowReceiver receiver, float radius) {
    float footprint = 0.5 * (abs(receiver.plane_gradient.x) + abs(receiver.plane_gradient.y));
    float guard_per_texel = kConcaveGuardSlope * frame.shadow_texel_depth;
    float lit = 0.0;
    for (int tap = 0; tap < kDiscTaps; ++tap) {
        vec2 offset = radius * kDiscTapsUnit[tap].xy;
        float r = radius * kDiscTapsUnit[tap].z;
        float depth = min(receiver.depth + dot(receiver.plane_gradient, offset), receiver.depth - r * guard_per_texel) -
                      footprint;
        lit += texture(building_shadow, vec3((receiver.texel + offset) * frame.shadow_texel_uv, depth));
    }
    return lit / float(kDiscTaps);
}

// The building's shadow at a point shadowLookup placed (its uv and biased depth, so that a shader that also reads
// the site's map, which shares the matrix, projects the point once).
float buildingSunVisibility(vec3 position_enu, vec3 normal_enu, vec2 uv, float depth) {
    // shadow_pcf_radius 0: hard shadows, the contact tap alone (the cheapest).
    if (frame.shadow_pcf_radius <= 0.0) return texture(building_shadow, vec3(uv, depth));
    ShadowReceiver receiver;
    float cosine = clamp(dot(normal_enu, frame.sun_direction), kShadowMinCosine, 1.0);
    if (!shadowReceiver(position_enu, normal_enu, cosine, receiver)) return 1.0;
    // Step 2. The 4 x 4 block about the texel corner nearest the point, then the ring.
    float ring = kRingTexels + frame.shadow_pcf_radius;
    vec2 centre = floor(receiver.texel + 0.5);
    vec2 sums = blockSums(receiver, centre + vec2(-1.0, -1.0)) + blockSums(receiver, centre + vec2(1.0, -1.0)) +
                blockSums(receiver, centre + vec2(-1.0, 1.0)) + blockSums(receiver, centre + vec2(1.0, 1.0));
    // Nothing blocks within 2 texels: lit (most fragments stop here, after 4 gathers). What this gives up: the
    // outermost rim of a penumbra wider than about 2 texels of radius, where V is above 0.9 anyway.
    if (sums.y == 0.0) return 1.0;
    sums += blockSums(receiver, centre + vec2(-ring, 0.0)) + blockSums(receiver, centre + vec2(ring, 0.0)) +
            blockSums(receiver, centre + vec2(0.0, -ring)) + blockSums(receiver, centre + vec2(0.0, ring));
    // Step 3. The penumbra's radius from the blockers' mean distance (in map depth; over the texel's depth it is
    // in texels), at most what the ring reaches less a texel for the taps' own footprint.
    float radius = min(sums.x / sums.y / frame.shadow_texel_depth * kSunRadiusTangent, ring - 1.0);
    if (radius > kContactTexels) return discVisibility(receiver, radius);
    return texture(building_shadow, vec3(uv, depth));
}

#endif
