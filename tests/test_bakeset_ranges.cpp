// Both bake set readers refuse what gusuku/formats/bakeset_ranges.h refuses: for every row of the table (iterated,
// so a new row is tested without a new test), the same value outside the row is written into a real bake of the
// mini site (its manifest.json, or a texel of its EXR) and into its runtime pack (the pack's manifest.json, or the
// texel of its KTX2), and loadBakeSet and loadRuntimePack must each refuse it in one line naming the field. Also:
// a pack.bin lightmap_scale that makes every lightmap texel too bright, and a NUL in a file name.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/site.h"
#include "gusuku/pack_loader/runtime_pack.h"
#include "gusuku/formats/bakeset_ranges.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/formats/ktx2.h"
#include "gusuku/formats/pack_geometry.h"
#include "gusuku_bake/bake_job.h"
#include "gusuku_bake/runtime_pack.h"
#include "mini_site.h"

namespace gusuku {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<uint8_t> readBytes(const std::string& path) {
    std::ifstream stream(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(stream), {});
}
void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

/// The message a reader gives, or "(accepted)" when it takes the set.
template <typename Read>
std::string refusalOf(Read read) {
    try {
        read();
    } catch (const InputError& error) {
        return error.what();
    } catch (const std::exception& error) {
        return std::string("(not an InputError) ") + error.what();
    }
    return "(accepted)";
}

/// Values outside the row: beyond each bound by as much as the bound's size (at least 1), and for a count a
/// fraction inside it.
std::vector<double> valuesOutside(const BakeSetRange& range) {
    std::vector<double> values = {range.maximum + std::max(1.0, std::fabs(range.maximum)),
                                  range.minimum - std::max(1.0, std::fabs(range.minimum))};
    if (range.whole_number) values.push_back(range.minimum + 0.5);
    return values;
}

class BakeSetRangesTest : public testing::GpuTest {
protected:
    /// The mini site with its SfM mesh (so the set has an occluder), baked once per test binary (2 samples) and
    /// packed into BAKESET/pack.
    static const std::string& bakedSet() { return folder_; }

    void SetUp() override {
        GpuTest::SetUp();
        if (!folder_.empty()) return;
        const std::string dir = testing::makeTemporaryDirectory("gusuku-ranges");
        testing::MiniSiteOptions site_options;
        site_options.samples_per_texel = 2;
        site_options.with_sfm_mesh = true;
        bake::BakeOptions options;
        options.output_dir = dir + "/bakeset";
        options.show_progress = false;
        ASSERT_TRUE(bake::runBake(context(), loadSiteConfig(testing::writeMiniSite(dir, site_options)), options).completed);
        bake::writeRuntimePack(options.output_dir);
        folder_ = options.output_dir;
    }

    static std::string manifestPath() { return folder_ + "/manifest.json"; }
    static std::string packPath() { return folder_ + "/pack"; }
    static std::string packManifestPath() { return packPath() + "/manifest.json"; }

    /// Both readers' messages for the set as it is now.
    static std::string exrRefusal() { return refusalOf([] { loadBakeSet(bakedSet()); }); }
    static std::string packRefusal() { return refusalOf([] { loadRuntimePack(packPath()); }); }

    static std::string folder_;
};
std::string BakeSetRangesTest::folder_;

/// Puts the file's original bytes back when the scope ends, so each case starts from the baked set.
class Restore {
public:
    explicit Restore(std::vector<std::string> paths) : paths_(std::move(paths)) {
        for (const std::string& path : paths_) bytes_.push_back(readBytes(path));
    }
    ~Restore() {
        for (size_t index = 0; index < paths_.size(); ++index) writeBytes(paths_[index], bytes_[index]);
    }

private:
    std::vector<std::string> paths_;
    std::vector<std::vector<uint8_t>> bytes_;
};

json readJson(const std::string& path) { return json::parse(readBytes(path)); }
void writeJson(const std::string& path, const json& document) {
    const std::string text = document.dump(2);
    writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

/// The row's JSON pointer with "#" replaced by the first slot that has the field (and a present sun, when the
/// row asks for one); empty when no slot of the set has it.
std::string pointerFor(const BakeSetRange& range, const json& manifest) {
    std::string pointer = range.field;
    const size_t hash = pointer.find('#');
    if (hash == std::string::npos) return manifest.contains(json::json_pointer(pointer)) ? pointer : "";
    for (size_t slot = 0; slot < manifest["slots"].size(); ++slot) {
        const std::string candidate = pointer.substr(0, hash) + std::to_string(slot) + pointer.substr(hash + 1);
        if (!manifest.contains(json::json_pointer(candidate))) continue;
        if (range.when_sun_present && !manifest["slots"][slot]["sun"]["present"].get<bool>()) continue;
        return candidate;
    }
    return "";
}

TEST_F(BakeSetRangesTest, TheBakedSetAndItsPackLoad) {
    EXPECT_EQ(exrRefusal(), "(accepted)");
    EXPECT_EQ(packRefusal(), "(accepted)");
}

// Every manifest row: the same value outside it, written into both manifests, is refused by both readers.
TEST_F(BakeSetRangesTest, BothReadersRefuseEveryManifestFieldOutsideItsRange) {
    const json manifest = readJson(manifestPath());
    for (const BakeSetRange& range : kBakeSetRanges) {
        if (range.source != BakeSetRangeSource::kManifest) continue;
        const std::string pointer = pointerFor(range, manifest);
        ASSERT_FALSE(pointer.empty()) << range.field << ": the baked set has no such field to vary";
        const bool is_array = manifest.at(json::json_pointer(pointer)).is_array();
        std::vector<json> replacements;
        for (const double value : valuesOutside(range)) {
            json replacement = manifest.at(json::json_pointer(pointer));
            (is_array ? replacement[0] : replacement) = value;
            replacements.push_back(replacement);
        }
        if (range.length_tolerance > 0.0) replacements.push_back(json::array({0.0, 0.0, 0.0}));
        for (const json& replacement : replacements) {
            const Restore restore({manifestPath(), packManifestPath()});
            for (const std::string& path : {manifestPath(), packManifestPath()}) {
                json edited = readJson(path);
                edited[json::json_pointer(pointer)] = replacement;
                writeJson(path, edited);
            }
            const std::string exr = exrRefusal(), pack = packRefusal();
            EXPECT_NE(exr.find(manifestPath() + ": " + pointer), std::string::npos)
                << range.field << " = " << replacement.dump() << ": the EXR set's reader says " << exr;
            EXPECT_NE(pack.find(packManifestPath() + ": " + pointer), std::string::npos)
                << range.field << " = " << replacement.dump() << ": the pack reader says " << pack;
        }
    }
}

/// The EXR and KTX2 file of the image a texel row covers, by the set's manifest.
std::pair<std::string, std::string> imageFilesFor(const BakeSetRange& range, const BakeSetManifest& manifest) {
    std::string exr;
    if (range.field == std::string(kBakeSetGroundNormal.field) || range.field == std::string(kBakeSetGroundHeightM.field))
        exr = manifest.ground_grid.geometry;
    else if (range.field == std::string(kBakeSetGroundAlbedo.field))
        exr = manifest.ground_grid.albedo;
    else  // the irradiance rows: a ground irradiance image, stored as floats in the pack as in the EXR
        exr = manifest.slots.front().ground_irradiance_with_building;
    return {exr, exr.substr(0, exr.rfind('.')) + ".ktx2"};
}

// Every texel row: texel (0, 0) set outside it in the EXR and in the pack's KTX2 is refused by both readers.
TEST_F(BakeSetRangesTest, BothReadersRefuseEveryTexelOutsideItsRange) {
    const BakeSetManifest manifest = loadBakeSet(bakedSet()).manifest;
    for (const BakeSetRange& range : kBakeSetRanges) {
        if (range.source != BakeSetRangeSource::kTexels) continue;
        const auto [exr_name, ktx2_name] = imageFilesFor(range, manifest);
        ASSERT_FALSE(exr_name.empty()) << range.field << ": the baked set has no such image";
        const std::string exr_path = bakedSet() + "/" + exr_name, ktx2_path = packPath() + "/" + ktx2_name;
        std::vector<std::vector<float>> replacements;  // the row's channels of texel (0, 0)
        for (const double value : valuesOutside(range)) replacements.push_back(std::vector<float>(range.channels, float(value)));
        if (range.length_tolerance > 0.0) replacements.push_back(std::vector<float>(range.channels, 0.0f));
        replacements.push_back(std::vector<float>(range.channels, std::numeric_limits<float>::quiet_NaN()));
        for (const std::vector<float>& replacement : replacements) {
            const Restore restore({exr_path, ktx2_path});
            ImageRGBA image = readFloatRgbaExr(exr_path);
            std::copy(replacement.begin(), replacement.end(), image.texels.begin() + range.first_channel);
            writeExr(exr_path, image, true);
            const std::vector<uint8_t> ktx2_bytes = readBytes(ktx2_path);
            Ktx2Image ktx2 = decodeKtx2(ktx2_bytes.data(), ktx2_bytes.size(), ktx2_path, Ktx2Format::kR32g32b32a32Sfloat);
            std::memcpy(ktx2.texels.data() + range.first_channel * sizeof(float), replacement.data(),
                        replacement.size() * sizeof(float));
            writeBytes(ktx2_path, encodeKtx2(ktx2));
            const std::string exr = exrRefusal(), pack = packRefusal();
            const std::string value = std::to_string(replacement.front());
            EXPECT_EQ(exr.rfind(exr_path + ": texel (0, 0)", 0), 0u) << range.field << " = " << value << ": " << exr;
            EXPECT_NE(exr.find(range.field), std::string::npos) << range.field << " = " << value << ": " << exr;
            EXPECT_EQ(pack.rfind(ktx2_path + ": texel (0, 0)", 0), 0u) << range.field << " = " << value << ": " << pack;
            EXPECT_NE(pack.find(range.field), std::string::npos) << range.field << " = " << value << ": " << pack;
        }
    }
}

// A lightmap_scale of 2^100 makes every lightmap texel about 1e30: the pack reader holds the texels after the
// scale to the irradiance row, as the EXR reader holds a lightmap EXR of 1e30.
TEST_F(BakeSetRangesTest, BothReadersRefuseLightmapsBrighterThanTheIrradianceRange) {
    const BakeSetManifest manifest = loadBakeSet(bakedSet()).manifest;
    {
        const std::string path = packPath() + "/pack.bin";
        const Restore restore({path});
        const std::vector<uint8_t> bytes = readBytes(path);
        PackGeometry geometry = decodePackGeometry(bytes.data(), bytes.size(), path);
        geometry.lightmap_scale = std::ldexp(1.0f, 100);
        writeBytes(path, encodePackGeometry(geometry));
        const std::string pack = packRefusal();
        const std::string lightmap = manifest.slots.front().building_irradiance;
        EXPECT_EQ(pack.rfind(packPath() + "/" + lightmap.substr(0, lightmap.rfind('.')) + ".ktx2: texel (", 0), 0u) << pack;
        EXPECT_NE(pack.find(kBakeSetTexelIrradiance.field), std::string::npos) << pack;
        EXPECT_NE(pack.find("lightmap_scale 1.26765e+30"), std::string::npos) << pack;
    }
    {
        const std::string path = bakedSet() + "/" + manifest.slots.front().building_irradiance;
        const Restore restore({path});
        ImageRGBA image = readFloatRgbaExr(path);
        for (size_t index = 0; index < image.texels.size(); ++index)
            if (index % 4 != 3) image.texels[index] = 1e30f;
        writeExr(path, image, true);
        const std::string exr = exrRefusal();
        EXPECT_EQ(exr.rfind(path + ": texel (0, 0) channel R: 1.00000002e+30 is outside [0, 1e+18]", 0), 0u) << exr;
        EXPECT_NE(exr.find(kBakeSetTexelIrradiance.field), std::string::npos) << exr;
    }
}

// A NUL in a file name would cut the path short where the system reads it: both readers name the field.
TEST_F(BakeSetRangesTest, BothReadersRefuseANulInAFileName) {
    const Restore restore({manifestPath(), packManifestPath()});
    for (const std::string& path : {manifestPath(), packManifestPath()}) {
        json edited = readJson(path);
        edited["slots"][0]["building_irradiance"] = std::string("building\0x.exr", 14);
        writeJson(path, edited);
    }
    EXPECT_EQ(exrRefusal(), manifestPath() + ": /slots/0/building_irradiance: holds a NUL character (\\u0000), which "
                                             "no file name may");
    EXPECT_EQ(packRefusal(), packManifestPath() + ": /slots/0/building_irradiance: holds a NUL character (\\u0000), "
                                                  "which no file name may");
}

}  // namespace
}  // namespace gusuku
