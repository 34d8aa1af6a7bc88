// The runtime's shadow lookups. Needs FrameUniforms; the includer declares the building map's two samplers:
// `building_shadow` (sampler2DShadow, bilinear compare) and `building_shadow_depths` (sampler2D, nearest).
//   - The building's shadow (buildingSunVisibility): V in [0, 1] (1 lit) with the penumbra the sun's real disc
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

// The slope-scaled bias grows with tan(angle between the normal and the sun), which is unbounded at grazing
// light: the cosine is held at or above this (about 87 degrees) so the tangent stays finite...
const float kShadowMinCosine = 0.05;
// ... and the tangent's share of the bias is capped at this (about 84 degrees): a larger bias would detach the
// shadow from the contact line of the surfaces that cast it, for a gain only on surfaces nearly edge-on to the sun.
const float kShadowMaxBiasTangent = 10.0;
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
const float kGoldenAngle = 2.39996323;

// The point's shadow-map coordinates and biased depth for the site's map; false outside the fitted window
// (nothing of the building can shade it there).
bool shadowLookup(vec3 position_enu, vec3 normal_enu, out vec2 uv, out float depth) {
    vec4 clip = frame.enu_to_shadow_clip * vec4(position_enu, 1.0);
    uv = clip.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
    float cosine = clamp(dot(normal_enu, frame.sun_direction), kShadowMinCosine, 1.0);
    float tangent = sqrt(1.0 - cosine * cosine) / cosine;
    depth = clip.z - frame.shadow_depth_bias * (1.0 + min(tangent, kShadowMaxBiasTangent));
    return true;
}

// The receiver as the building's map sees it. The map's matrix is orthographic with orthogonal rows
// (shadow_fit.h): |row x| = 2 / window side, |row z| = 1 / depth range.
struct ShadowReceiver {
    vec2 texel;           // position in texels (texel i's centre at i + 0.5)
    float depth;          // the offset point's map depth, less the margin
    vec2 plane_gradient;  // the receiver plane's map depth per texel step in x and y
    float texel_m;        // one texel's side, metres
    float depth_range_m;  // map depth 0 to 1, metres
    float guard_per_texel;  // kConcaveGuardSlope texels' side in map depth
};

bool shadowReceiver(vec3 position_enu, vec3 normal_enu, out ShadowReceiver receiver) {
    mat4 m = frame.enu_to_shadow_clip;
    vec3 row_x = vec3(m[0][0], m[1][0], m[2][0]);
    vec3 row_y = vec3(m[0][1], m[1][1], m[2][1]);
    vec3 row_z = vec3(m[0][2], m[1][2], m[2][2]);
    receiver.texel_m = 2.0 * frame.shadow_texel_uv / length(row_x);
    receiver.depth_range_m = 1.0 / length(row_z);
    float cosine = clamp(dot(normal_enu, frame.sun_direction), kShadowMinCosine, 1.0);
    float sine = sqrt(1.0 - cosine * cosine);
    vec3 offset_enu = position_enu + normal_enu * (kNormalOffsetTexels * receiver.texel_m * sine);
    vec4 clip = m * vec4(offset_enu, 1.0);
    vec2 uv = clip.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
    receiver.texel = uv / frame.shadow_texel_uv;
    receiver.depth = clip.z - kPlaneMarginTexels * receiver.texel_m / receiver.depth_range_m;
    receiver.guard_per_texel = kConcaveGuardSlope * receiver.texel_m / receiver.depth_range_m;
    // Along the plane, a step of one texel in map x moves the depth by -(n.x / n.z) texel_m (n in the map's
    // unit axes, n.z = -cosine towards the sun), held to the same grazing limit as the site's bias.
    vec2 slope = vec2(dot(normalize(row_x), normal_enu), dot(normalize(row_y), normal_enu)) / cosine;
    float steepest = length(slope);
    if (steepest > kShadowMaxBiasTangent) slope *= kShadowMaxBiasTangent / steepest;
    receiver.plane_gradient = slope * (receiver.texel_m / receiver.depth_range_m);
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
    vec4 limit = min(plane_depth, receiver.depth - lateral * receiver.guard_per_texel);
    vec4 blocks = vec4(lessThan(stored, limit));
    return vec2(dot(blocks, receiver.depth - stored), dot(blocks, vec4(1.0)));
}

vec4 gatherDepths(vec2 corner) { return textureGather(building_shadow_depths, corner * frame.shadow_texel_uv, 0); }

// The wide penumbra: bilinear compare taps on a disc of `radius` texels, each against the plane at the tap less
// the plane's depth change across the hardware's 2 x 2 footprint.
float discVisibility(ShadowReceiver receiver, float radius) {
    float footprint = 0.5 * (abs(receiver.plane_gradient.x) + abs(receiver.plane_gradient.y));
    float lit = 0.0;
    for (int tap = 0; tap < kDiscTaps; ++tap) {
        float r = radius * sqrt((float(tap) + 0.5) / float(kDiscTaps));
        float angle = float(tap) * kGoldenAngle;
        vec2 offset = r * vec2(cos(angle), sin(angle));
        float depth = min(receiver.depth + dot(receiver.plane_gradient, offset),
                          receiver.depth - r * receiver.guard_per_texel) - footprint;
        lit += texture(building_shadow, vec3((receiver.texel + offset) * frame.shadow_texel_uv, depth));
    }
    return lit / float(kDiscTaps);
}

float buildingSunVisibility(vec3 position_enu, vec3 normal_enu) {
    vec2 uv;
    float depth;
    if (!shadowLookup(position_enu, normal_enu, uv, depth)) return 1.0;
    // shadow_pcf_radius 0: hard shadows, the contact tap alone (the cheapest).
    if (frame.shadow_pcf_radius <= 0.0) return texture(building_shadow, vec3(uv, depth));
    ShadowReceiver receiver;
    if (!shadowReceiver(position_enu, normal_enu, receiver)) return 1.0;
    // Step 2. The 4 x 4 block about the texel corner nearest the point, then the ring.
    float ring = kRingTexels + frame.shadow_pcf_radius;
    vec2 blocks[8] = vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0), vec2(-ring, 0.0),
                            vec2(ring, 0.0), vec2(0.0, -ring), vec2(0.0, ring));
    vec2 centre = floor(receiver.texel + 0.5);
    vec2 sums = vec2(0.0);
    for (int block = 0; block < 4; ++block)
        sums += blockerSums(receiver, centre + blocks[block], gatherDepths(centre + blocks[block]));
    // Nothing blocks within 2 texels: lit (most fragments stop here, after 4 gathers). What this gives up: the
    // outermost rim of a penumbra wider than about 2 texels of radius, where V is above 0.9 anyway.
    if (sums.y == 0.0) return 1.0;
    for (int block = 4; block < 8; ++block)
        sums += blockerSums(receiver, centre + blocks[block], gatherDepths(centre + blocks[block]));
    // Step 3. The penumbra's radius from the blockers' mean distance, at most what the ring reaches less a texel
    // for the taps' own footprint.
    float distance_m = sums.x / sums.y * receiver.depth_range_m;
    float radius = min(distance_m * kSunRadiusTangent / receiver.texel_m, ring - 1.0);
    if (radius > kContactTexels) return discVisibility(receiver, radius);
    return texture(building_shadow, vec3(uv, depth));
}

#endif
