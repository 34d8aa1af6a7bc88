#pragma once
// An independent truth for the bench's own (issue 20 items 6 and 9): Blender Cycles' renders of the site section's
// poses (bench/cycles/cycles_view_render.py: the same camera, sky, sun, Lambertian surfaces and bounces, built from
// the site's model files by Blender's importer, no gusuku code in between), read from gusuku-bench --cycles-truth
// DIR at the baked instant (the slot the renders were lit by). Per pose it reports the camera tracer's difference
// from Cycles beside the tracer's own seed-to-seed difference, and the building's mean linear colour per material
// in the runtime's composite, the tracer's truth and Cycles'.

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "bench_run.h"

namespace gusuku::bench {

/// One pose's renders, as cycles_view_render.py writes them in DIR: each frame twice, with two seeds (suffix
/// _b), whose mean is Cycles' estimate and whose difference measures its own noise.
struct CyclesView {
    ImageRGBA with_building[2];         ///< DIR/NAME_building.exr, NAME_building_b.exr: linear Rec.709 radiance
    ImageRGBA without_building[2];      ///< DIR/NAME_site.exr, NAME_site_b.exr
    std::vector<uint32_t> material_ids; ///< DIR/NAME_materials.exr red channel: 0 none, k: materials[k - 1]
    std::vector<std::string> materials; ///< DIR/materials.json
};

/// The mean of two frames of the same size.
ImageRGBA meanOf(const ImageRGBA& a, const ImageRGBA& b);

/// Reads pose `name`'s renders. InputError naming the file when one is missing, unreadable or not width x height,
/// or materials.json is not a list of names.
CyclesView readCyclesView(const std::string& folder, const std::string& name, uint32_t width, uint32_t height);

/// Two linear frames' difference over the mask (empty: every pixel): the mean and the root mean square of the
/// per-pixel CIEDE2000 after the bench's neutral camera response at this exposure; the per-pixel luminance
/// difference's root mean square over the mean luminance; the ratio of mean luminances minus one.
struct FrameDifference {
    double mean_de00 = 0.0, rms_de00 = 0.0, rms_relative_luminance = 0.0, luminance_bias = 0.0;
    size_t pixels = 0;
};
FrameDifference frameDifference(const ImageRGBA& frame, const ImageRGBA& reference, float exposure,
                                const std::vector<uint8_t>& mask);

/// Pixels of one building material in both renders' interior (the pixel and its four neighbours carry it in
/// Cycles' id pass), and their mean linear RGB in the runtime's composite (8-bit sRGB decoded, divided by the
/// exposure it was given), the tracer's truth and Cycles'.
struct MaterialColour {
    std::string name;
    size_t pixels = 0;
    glm::dvec3 runtime{0.0}, tracer{0.0}, cycles{0.0};
};
std::vector<MaterialColour> materialColours(const CyclesView& cycles, const std::vector<uint8_t>& composite,
                                            float composite_exposure, const ImageRGBA& tracer);

/// The pose's check at the baked instant: prints its rows and returns results["site"]["views"][i]["cycles"].
/// `agrees` is set false when the tracer's difference from Cycles (CIEDE2000 or relative luminance, with and
/// without the building) is above its seed-to-seed difference.
Json checkPoseAgainstCycles(Bench& bench, const NamedView& named, double utc_seconds, const ConditionFrames& frames,
                            const ImageRGBA& truth_seed2, const std::vector<uint8_t>& composite,
                            const std::vector<uint8_t>& mask, bool& agrees);

}  // namespace gusuku::bench
