// bench/cycles' lighting (issue 11.1): `gusuku-bake converge --export-lighting` writes a slot's sky, sun disc
// removed, laid out for Blender's world lookup, and its sun. Checked against the tracer's own sky lookup
// (skyRadianceCpu, the CPU twin of sky_sampling.glsl) through Blender's equirectangular convention as Cycles'
// kernel defines it (direction_to_equirectangular: u = (atan2(y, x) - pi) / -2 pi, v = (acos(z) - pi / 2) / -pi,
// v = 1 at the top, the zenith), on a sky that differs in every direction and whose north is turned.
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/cycles_lighting_export.h"
#include "gusuku_bake/slot_lighting.h"
#include "mini_site.h"

namespace gusuku::bake {
namespace {

using std::numbers::pi;

TEST(CyclesLightingExportTest, BlenderReadsTheSkyTheTracerSees) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-cycles-lighting");
    const std::string site_path = gusuku::testing::writeMiniSite(dir);
    // A sky that changes with azimuth and height, so a wrong turn or flip shows: R a ramp over the image's
    // columns, G over its rows, B 1.
    ImageRGBA sky;
    sky.width = 64;
    sky.height = 32;
    sky.texels.resize(size_t(sky.width) * sky.height * 4);
    for (int y = 0; y < sky.height; ++y)
        for (int x = 0; x < sky.width; ++x) {
            float* t = sky.texel(x, y);
            t[0] = 0.1f + float(x), t[1] = 0.1f + float(y), t[2] = 1.0f, t[3] = 1.0f;
        }
    SiteConfig site = loadSiteConfig(site_path);
    writeHdr(site.sunny_sky.path, sky);
    site.sunny_sky.north_azimuth_in_image_deg = 100.0;
    const BakeSlot* sunny = nullptr;
    for (const BakeSlot& slot : site.bake.slots)
        if (slot.sky == SlotSky::Sunny) sunny = &slot;
    ASSERT_NE(sunny, nullptr);
    exportSlotLightingForCycles(site, sunny->name, dir + "/lighting");

    const ImageRGBA exported = readRadianceMap(dir + "/lighting/sky_" + sunny->name + ".hdr");
    ASSERT_EQ(exported.width, sky.width);
    ASSERT_EQ(exported.height, sky.height);
    const PreparedSky prepared = prepareSky(site.sunny_sky);
    int checked = 0;
    for (int row = 0; row < exported.height; ++row)
        for (int column = 0; column < exported.width; ++column) {
            // Blender's direction at this texel's centre (image row 0 is v = 1).
            const double u = (column + 0.5) / exported.width, v = 1.0 - (row + 0.5) / exported.height;
            const double phi = pi - 2.0 * pi * u;          // atan2(y, x)
            const double polar = pi / 2.0 - pi * (v - 0.5);  // acos(z)
            const glm::dvec3 direction(std::sin(polar) * std::cos(phi), std::sin(polar) * std::sin(phi),
                                       std::cos(polar));
            const glm::dvec3 expected = skyRadianceCpu(prepared.tables, direction);
            const float* got = exported.texel(column, row);
            // RGBE keeps 8 bits of mantissa: 1 % of the texel's largest channel.
            const double tolerance = 0.01 * std::max({expected.r, expected.g, expected.b});
            EXPECT_NEAR(got[0], expected.r, tolerance) << "column " << column << " row " << row;
            EXPECT_NEAR(got[1], expected.g, tolerance) << "column " << column << " row " << row;
            ++checked;
        }
    EXPECT_EQ(checked, 64 * 32);

    // The sun: the slot's, as the bake traces it.
    std::ifstream stream(dir + "/lighting/sun_" + sunny->name + ".json");
    std::stringstream text;
    text << stream.rdbuf();
    const SlotLighting lighting = lightSlot(site, *sunny, prepared, nullptr);
    ASSERT_TRUE(lighting.sun.present);
    EXPECT_NE(text.str().find("\"present\": true"), std::string::npos) << text.str();
    char direction[128];
    std::snprintf(direction, sizeof direction, "\"direction_enu\": [%.9g, %.9g, %.9g]", lighting.sun.direction_enu.x,
                  lighting.sun.direction_enu.y, lighting.sun.direction_enu.z);
    EXPECT_NE(text.str().find(direction), std::string::npos) << text.str();
}

}  // namespace
}  // namespace gusuku::bake
