// The baker's light-transport core: an irradiance estimate at a point with a normal, from paths that gather
// sky light (the cosine lobe, plus the importance-sampled map by MIS when the sky is uneven), sun light at
// every surface they reach (next-event estimation to the disc; the disc is taken out of the sky map so only
// this estimator sees it) and emission, over up to max_bounces diffuse reflections with Russian roulette.
//
// The convention at a surface (the lightmap texel and every path vertex alike, as Cycles and Mitsuba do): light
// is gathered with the cosine lobe about the shading normal, and directions below the geometric face plane
// contribute nothing (the ray would leave through the surface itself). So a texel whose smoothed normal leans
// theta from its face under a uniform sky L gets pi L (1 + cos theta) / 2, not pi L.
//
// Units: the estimator returns irradiance E = integral of L cos over the hemisphere. At a diffuse surface of
// albedo rho the outgoing radiance is rho / pi * E, so a cosine-sampled bounce multiplies the path weight by
// rho: pi (cos / pdf) * rho / pi.
//
// The includer provides, before including: sampling.glsl, bvh_traverse.glsl, scene_shading.glsl,
// sky_sampling.glsl, and the uniforms below through a struct `PathSettings`.
#ifndef GUSUKU_IRRADIANCE_PATHS_GLSL
#define GUSUKU_IRRADIANCE_PATHS_GLSL

#include "constants.glsl"

struct PathSettings {
    uint max_bounces;       // surface reflections whose light counts (0: sky and emitters seen directly only)
    uint skip_flags;        // triangles with any of these flags are invisible (the "without building" pass)
    bool sun_present;
    vec3 sun_direction;     // unit, ENU
    float sun_cos_max;      // cosine of the disc's angular radius
    vec3 sun_irradiance;    // irradiance on a plane facing the sun (normal incidence), linear RGB
    float ray_offset;       // metres along the normal, to leave the surface a ray starts on
    bool sky_next_event;    // also sample the sky map at each vertex (MIS); off: the cosine lobe alone
};

uint g_rays_traced = 0u;

// Russian roulette starts only after this many reflections. Earlier, it ran from the second reflection on, with
// a survival chance of the path weight (rho1 rho2, about 0.1 on the sample site): a surviving path carried 10
// times the weight into the sun's next-event estimate at its second reflection, so sunlight bounced twice came as
// a rare, bright yes-or-no that the Sobol draws could not stratify (it took a 1D random number). Starting later
// cuts the error for the rays spent and makes it fall faster with the samples (gusuku-bake converge on the
// sample; the figures are in docs/measurements.md). Past three reflections the weight
// is rho^3 (under 0.03 for stone and plaster), where roulette's extra noise is small and it saves long paths.
// A specialisation constant (constant_id 3, IRRADIANCE_BOUNCES_BEFORE_ROULETTE_CONSTANT in
// bake_irradiance_interface.h) rather than a push constant: every production pipeline keeps this default, so the
// comparison is folded at compile time, and only the test that runs the estimator before issue 11.1 (1) beside
// this one makes a pipeline of its own with another value.
#if defined(IRRADIANCE_BOUNCES_BEFORE_ROULETTE_CONSTANT) && IRRADIANCE_BOUNCES_BEFORE_ROULETTE_CONSTANT != 3
#error "irradiance_paths.glsl declares kBouncesBeforeRoulette as constant_id 3"
#endif
layout(constant_id = 3) const uint kBouncesBeforeRoulette = 3u;
// Sky next-event rays at the query point (depth 0), a power of two; 1 at every later vertex. Their draws are one
// aligned block of the sample's Sobol sequence (rngNext2Split), and the MIS weights count them (Veach's
// multi-sample power heuristic: n_map p_map against p_cos), so the estimate stays unbiased for any count.
uint g_sky_rays_at_point = 1u;

bool traceOccluded(vec3 origin, vec3 direction, PathSettings settings) {
    g_rays_traced++;
    return bvhOccluded(origin, direction, 1e30, settings.skip_flags);
}

// A double-sided face of a closed part (baker/include/gusuku_bake/closed_parts.h) hit from behind (by its winding)
// scores this much toward a texel's back-face share, a one-sided one 1; the back of an open double-sided sheet
// (a roof of one layer) scores nothing: it is the sheet's other visible side, and a texel under it is in the
// open (issue 21 item 7: a pavilion's floor under a wide roof saw its back in over 90 % of its rays). The bake marks a texel invalid when its mean score passes kMaxBackfaceFraction = 0.1
// (baker/src/bake_outputs.h), so one-sided backs must fill more than 10 % of its first rays (as before) and
// closed double-sided backs more than 90 %: a closed part's inside sees back faces in every direction (100 %),
// while a texel outside sees at most half of a closed part's faces from behind (where it touches it). Why not 1: double-sided is how most real
// models mark every material, so their backs alone are the only sign of a texel inside a closed part.
const float kDoubleSidedBackfaceScore = 0.1 / 0.9;

// Sun irradiance at a surface point: disc sampled uniformly, one shadow ray. Its own code path so that tests
// can check it in isolation (E = I_sun cos theta on a plane tilted by theta, 0 in shadow). `face_normal` is the
// geometric normal on the shading normal's side: a sun below the face plane gives nothing (the convention above).
vec3 sunIrradianceAt(vec3 position, vec3 normal, vec3 face_normal, inout Rng rng, PathSettings settings) {
    if (!settings.sun_present) return vec3(0.0);
    vec3 direction = sampleCone(settings.sun_direction, settings.sun_cos_max, rngNext2(rng));
    float cos_theta = dot(normal, direction);
    if (cos_theta <= 0.0 || dot(face_normal, direction) <= 0.0) return vec3(0.0);
    if (traceOccluded(position + normal * settings.ray_offset, direction, settings)) return vec3(0.0);
    return settings.sun_irradiance * cos_theta;
}

// One-sample estimate of the indirect irradiance E_ind at (position, normal, face_normal): everything but the
// direct sun at this point. `face_normal` is the geometric normal on the shading normal's side (the convention
// above). `backface_score` is the first ray's share of evidence that the point lies inside geometry (a texel
// behind a wall): 1 when it hits the back of a one-sided surface, kDoubleSidedBackfaceScore when it hits a
// double-sided surface from behind by its winding, else 0; the caller marks points whose mean score is too high
// invalid. Only the validity test looks at a double-sided surface's winding: its shading is the same from
// either side.
vec3 estimateIndirectIrradiance(vec3 position, vec3 normal, vec3 face_normal, inout Rng rng, PathSettings settings,
                                out float backface_score) {
    backface_score = 0.0;
    vec3 irradiance = vec3(0.0);
    vec3 path_weight = vec3(1.0);
    vec3 vertex_position = position;
    vec3 vertex_normal = normal;
    vec3 vertex_face_normal = face_normal;
    for (uint depth = 0u;; ++depth) {
        vec3 origin = vertex_position + vertex_normal * settings.ray_offset;

        // Sky by importance sampling the map, weighted against the cosine lobe (power heuristic). Skipped for
        // smooth skies (the caller decides from the map): there the cosine lobe alone is nearly as good per
        // sample and costs one ray per vertex instead of two.
        // The map is drawn from only in the rows that can hold a direction above both the shading and the face
        // plane (sky_sampling.glsl), and both strategies' MIS weights use that conditioned density.
        uint sky_rays = depth == 0u ? g_sky_rays_at_point : 1u;
        ivec2 sky_rows = ivec2(0);
        float sky_rows_probability = 0.0;
        if (settings.sky_next_event) {
            ivec2 shading_rows = skyRowsFacing(vertex_normal);
            ivec2 face_rows = skyRowsFacing(vertex_face_normal);
            sky_rows = ivec2(max(shading_rows.x, face_rows.x), min(shading_rows.y, face_rows.y));
            sky_rows_probability = skyRowsProbability(sky_rows);
            for (uint k = 0u; k < sky_rays; ++k) {
                float sky_pdf;
                vec2 draw = sky_rays == 1u ? rngNext2(rng) : rngNext2Split(rng, k, sky_rays);
                vec3 sky_direction = sampleSkyDirectionInRows(draw, sky_rows, sky_pdf);
                float sky_cos = dot(vertex_normal, sky_direction);
                if (sky_cos > 0.0 && sky_pdf > 0.0 && dot(vertex_face_normal, sky_direction) > 0.0 &&
                    !traceOccluded(origin, sky_direction, settings)) {
                    float mis = powerHeuristic(float(sky_rays) * sky_pdf, sky_cos / kPi);
                    irradiance += path_weight * skyRadiance(sky_direction) *
                                  (sky_cos / (float(sky_rays) * sky_pdf) * mis);
                }
            }
            if (sky_rays > 1u) rng.dimension++;
        }
        // The sun lights every surface the path reaches; at the query point itself it is the real-time term.
        if (depth > 0u)
            irradiance += path_weight * sunIrradianceAt(vertex_position, vertex_normal, vertex_face_normal, rng, settings);

        // Cosine-sampled continuation: sky on a miss (the other MIS half), emission and a bounce on a hit. A
        // direction below the face plane ends the path with nothing (it would leave through the surface); the
        // MIS weights stay those of the full lobe and map, as both strategies see the same clipped integrand.
        vec3 direction = sampleCosineHemisphere(vertex_normal, rngNext2(rng));
        if (dot(vertex_face_normal, direction) <= 0.0) break;
        float cos_pdf = max(dot(vertex_normal, direction), 0.0) / kPi;
        BvhHit hit;
        g_rays_traced++;
        if (!bvhTraceClosest(origin, direction, 1e30, settings.skip_flags, hit)) {
            float sky_pdf;
            vec3 sky_radiance = skyRadianceAndPdf(direction, sky_pdf);
            // The direction is above both planes, so inside sky_rows: the conditioned density is this over the
            // rows' probability (none when they hold no light: the map strategy drew nothing there).
            float map_pdf = sky_rows_probability > 0.0 ? sky_pdf / sky_rows_probability : 0.0;
            float mis = settings.sky_next_event ? powerHeuristic(cos_pdf, float(sky_rays) * map_pdf) : 1.0;
            irradiance += path_weight * kPi * sky_radiance * mis;
            break;
        }
        SurfacePoint surface = evaluateSurface(hit.triangle_index, hit.barycentric_u, hit.barycentric_v, direction);
        if (!surface.front_face && !surface.double_sided) {
            // A one-sided back is evidence of lying inside geometry (a wall's inside, the ground from below), so the
            // validity score counts it whatever the part. Its light: a closed part's back is the inside of a solid,
            // and no light arrives from there; an open part's back (a one-sided cut-out card, a leaf, a sign) is
            // the sheet's other side, shaded as a double-sided face's, as Cycles shades it and as the runtime
            // draws it (both faces lit). Ending such paths dark made the house's vine and tree cards black from
            // behind in the camera tracer and darkened the wall behind them in the bake.
            if (depth == 0u) backface_score = 1.0;
            if (surface.closed_part) break;
        }
        // A double-sided face's back is evidence only on a closed part: an open sheet's back is its other side.
        if (depth == 0u && !surface.front_face && surface.closed_part) backface_score = kDoubleSidedBackfaceScore;
        irradiance += path_weight * kPi * surface.emission;
        if (depth >= settings.max_bounces) break;

        path_weight *= surface.albedo;
        if (depth + 1u >= kBouncesBeforeRoulette) {
            // Russian roulette on the path weight: unbiased, and ends dark paths early; only past the first
            // kBouncesBeforeRoulette reflections (see there).
            float survival = clamp(max(path_weight.r, max(path_weight.g, path_weight.b)), 0.05, 0.95);
            if (rngNext(rng) >= survival) break;
            path_weight /= survival;
        }
        vertex_position = origin + direction * hit.t;
        vertex_normal = surface.shading_normal;
        vertex_face_normal = surface.geometric_normal;
        // Keep the continuation on the geometric side the ray arrived from.
        vertex_position += surface.geometric_normal * settings.ray_offset;
    }
    return irradiance;
}

#endif
