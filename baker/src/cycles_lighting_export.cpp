#include "gusuku_bake/cycles_lighting_export.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/image.h"
#include "gusuku_bake/slot_lighting.h"

namespace gusuku::bake {

void exportSlotLightingForCycles(const SiteConfig& site, const std::string& slot_name, const std::string& folder) {
    const BakeSlot* slot = nullptr;
    for (const BakeSlot& candidate : site.bake.slots)
        if (candidate.name == slot_name) slot = &candidate;
    if (slot == nullptr) throw std::invalid_argument("no slot named '" + slot_name + "' in " + site.file);
    const PreparedSky sunny = prepareSky(site.sunny_sky);
    std::optional<PreparedSky> overcast;
    if (site.overcast_sky) overcast = prepareSky(*site.overcast_sky);
    const SlotLighting lighting = lightSlot(site, *slot, sunny, overcast ? &*overcast : nullptr);
    const SkySamplingTables& tables = lighting.sky->tables;

    // Blender: u_b = 0.5 - atan2(y, x) / 2 pi. With the azimuth A east of north, atan2(y, x) = 90 deg - A, so
    // u_b = 0.25 + A / 360. The tracer (sky_sampling.glsl) reads column u_g = (A + north) / 360. Rows agree
    // (both polar angle from the zenith down).
    ImageRGBA image;
    image.width = tables.width;
    image.height = tables.height;
    image.texels.assign(size_t(image.width) * size_t(image.height) * 4, 0.0f);
    for (int x = 0; x < image.width; ++x) {
        const double u_blender = (x + 0.5) / image.width;
        const double azimuth_deg = (u_blender - 0.25) * 360.0;
        double u_tracer = (azimuth_deg + tables.north_azimuth_in_image_deg) / 360.0;
        u_tracer -= std::floor(u_tracer);
        const int source_x = std::min(int(u_tracer * image.width), image.width - 1);
        for (int y = 0; y < image.height; ++y) {
            const float* source = &tables.radiance_rgba[(size_t(y) * size_t(image.width) + size_t(source_x)) * 4];
            float* target = image.texel(x, y);
            for (int c = 0; c < 3; ++c) target[c] = source[c];
            target[3] = 1.0f;
        }
    }
    std::filesystem::create_directories(folder);
    writeFileAtomicallyKeepingExtension(folder + "/sky_" + slot_name + ".hdr",
                                        [&](const std::string& path) { writeHdr(path, image); });

    const SunLight& sun = lighting.sun;
    char text[512];
    std::snprintf(text, sizeof text,
                  "{\"present\": %s, \"direction_enu\": [%.9g, %.9g, %.9g], \"irradiance_rgb\": [%.9g, %.9g, %.9g], "
                  "\"angular_radius_deg\": %.9g}\n",
                  sun.present ? "true" : "false", sun.direction_enu.x, sun.direction_enu.y, sun.direction_enu.z,
                  sun.irradiance_rgb.x, sun.irradiance_rgb.y, sun.irradiance_rgb.z, sun.angular_radius_deg);
    writeBytesAtomically(folder + "/sun_" + slot_name + ".json", text, std::strlen(text));
}

}  // namespace gusuku::bake
