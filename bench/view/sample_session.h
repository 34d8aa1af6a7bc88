#pragma once
// The sample session (docs/session.md): a walk around the bake's building through its bake day, 08:00 to 17:00 on
// the site's clock, with a cloud passing after noon; the camera frames path-traced WITHOUT the building by the
// bench's truth renderer (as gusuku-render's --camera sample), at few samples and a small size so that making it
// takes seconds. A fresh clone gets one from scripts/run-sample.sh.

#include <cstdint>
#include <string>

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/gpu/gpu_device.h"
#include "view_session.h"

namespace gusuku::view {

struct SampleWalkOptions {
    uint32_t frames = 28;                  ///< from 08:00 to 17:00, evenly spaced (20 minutes apart)
    uint32_t width = 256, height = 144;
    uint32_t samples_per_pixel = 8;        ///< path-traced samples a pixel, denoised
    double horizontal_fov_deg = 55.0;
    double first_hour = 8.0, last_hour = 17.0;  ///< site clock
    bool show_progress = true;
};

/// Frame `index` of `count`'s cloud cover: a cloud passing the sun between 12:30 and 14:00 (peak 0.8 at 13:15),
/// clear otherwise.
float sampleCloudCover(double site_clock_hours);

/// Makes the walk's session in memory (every frame's rgba8 filled; exposure fixed for the whole walk, the middle
/// grey of the median frame, so the day's light changes as it does for a camera held at one exposure). InputError
/// for the site's files (the manifest's site.json).
Session makeSampleSession(const GpuDevice& gpu, const std::string& bake_set_folder, const BakeSetData& bake_set,
                          const SampleWalkOptions& options);

}  // namespace gusuku::view
