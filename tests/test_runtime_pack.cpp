// The runtime pack (docs/bakeset.md, "The runtime pack") on a real bake of the mini site: `gusuku-bake pack`
// writes it; loadRuntimePack (standard library only) reads back what loadBakeSet reads from the EXRs and glbs,
// exactly but for the lightmaps' E5B9G9R9 rounding (within half a step of the shared exponent); the runtime draws
// the same bytes from either; and every kind of bad pack file is refused in one line naming the file and field,
// through the C API too.

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake_output_checks.h"
#include "bake_command.h"
#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/site.h"
#include "gusuku/loader/gusuku_loader.h"
#include "gusuku/pack_loader/runtime_pack.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/formats/ktx2.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku_bake/bake_job.h"
#include "mini_site.h"

namespace gusuku {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> readBytes(const std::string& path) {
    std::ifstream stream(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(stream), {});
}
void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

class RuntimePackTest : public testing::GpuTest {
protected:
    /// The mini site baked once per test binary (2 samples) and packed by `gusuku-bake pack`.
    static const std::string& bakedSet() { return folder_; }

    void SetUp() override {
        GpuTest::SetUp();
        if (!folder_.empty()) return;
        const std::string dir = testing::makeTemporaryDirectory("gusuku-runtime-pack");
        testing::MiniSiteOptions site_options;
        site_options.samples_per_texel = 2;
        bake::BakeOptions options;
        options.output_dir = dir + "/bakeset";
        options.show_progress = false;
        ASSERT_TRUE(bake::runBake(context(), loadSiteConfig(testing::writeMiniSite(dir, site_options)), options).completed);
        const testing::CommandResult packed = testing::runBakeCommand({"pack", options.output_dir}, dir);
        ASSERT_EQ(packed.exit_code, 0) << packed.stderr_text;
        EXPECT_NE(packed.stdout_text.find("runtime pack:"), std::string::npos) << packed.stdout_text;
        folder_ = options.output_dir;
    }

    /// A copy of the pack to break, in a fresh folder.
    std::string packCopy(const std::string& name) {
        const std::string copy = testing::makeTemporaryDirectory("gusuku-pack-" + name) + "/pack";
        fs::copy(bakedSet() + "/pack", copy);
        return copy;
    }

    static std::string folder_;
};
std::string RuntimePackTest::folder_;

TEST_F(RuntimePackTest, ReadsBackWhatTheBakeSetHolds) {
    const BakeSetData exr = loadBakeSet(bakedSet());
    const BakeSetData pack = loadRuntimePack(bakedSet());  // a bake set folder: its pack/ is read
    gusuku::testing::expectSameMeshGeometry(pack.building, exr.building);
    ASSERT_EQ(pack.building.materials.size(), exr.building.materials.size());
    for (size_t index = 0; index < exr.building.materials.size(); ++index) {
        EXPECT_EQ(pack.building.materials[index].base_color_factor, exr.building.materials[index].base_color_factor);
        EXPECT_EQ(pack.building.materials[index].base_color_texture, exr.building.materials[index].base_color_texture);
    }
    ASSERT_EQ(pack.building.textures.size(), exr.building.textures.size());
    for (size_t index = 0; index < exr.building.textures.size(); ++index)
        EXPECT_EQ(pack.building.textures[index].rgba8, exr.building.textures[index].rgba8);
    EXPECT_EQ(pack.occluder.positions, exr.occluder.positions);
    EXPECT_EQ(pack.occluder.indices, exr.occluder.indices);
    EXPECT_EQ(pack.ground_geometry.rgba, exr.ground_geometry.rgba);
    EXPECT_EQ(pack.ground_albedo.rgba, exr.ground_albedo.rgba);
    EXPECT_EQ(pack.manifest.slots, exr.manifest.slots);
    EXPECT_EQ(pack.manifest.site, exr.manifest.site);
    EXPECT_EQ(pack.manifest.ground_grid, exr.manifest.ground_grid);
    EXPECT_EQ(pack.manifest.building, exr.manifest.building);
    EXPECT_EQ(pack.manifest.occluder, exr.manifest.occluder);
    ASSERT_EQ(pack.slots.size(), exr.slots.size());
    for (size_t slot = 0; slot < exr.slots.size(); ++slot) {
        EXPECT_EQ(pack.slots[slot].ground_with.rgba, exr.slots[slot].ground_with.rgba);
        EXPECT_EQ(pack.slots[slot].ground_without.rgba, exr.slots[slot].ground_without.rgba);
        const std::vector<float>& packed = pack.slots[slot].building.rgba;
        const std::vector<float>& original = exr.slots[slot].building.rgba;
        ASSERT_EQ(packed.size(), original.size());
        for (size_t texel = 0; texel < original.size() / 4; ++texel) {
            const float* in = &original[texel * 4];
            const float largest = std::max({in[0], in[1], in[2]});
            EXPECT_EQ(packed[texel * 4 + 3], in[3]) << "validity of texel " << texel;
            for (int channel = 0; channel < 3; ++channel)  // half a step; a step is at most largest / 255.75
                ASSERT_LE(std::abs(packed[texel * 4 + channel] - in[channel]), largest / 511.5f + 1e-30f)
                    << "slot " << slot << " texel " << texel << " channel " << channel;
        }
    }
}

TEST_F(RuntimePackTest, TheRuntimeDrawsTheSameBytesFromThePackAsFromTheExrs) {
    RuntimeOptions options;
    options.frame_width = 96;
    options.frame_height = 72;
    const std::vector<uint8_t> camera(size_t(96) * 72 * 4, 120);
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = CameraIntrinsics::fromFieldOfView(96, 72, 60.0);
    frame.pose = CameraPose::lookingAt({6, -8, 4}, {0, 0, 1});
    frame.utc_unix_seconds = 1782000000.0;
    frame.colour_match = ColourMatch::kOff;
    std::vector<uint8_t> from_exr(camera.size()), from_pack(camera.size());
    Runtime::open(context(), loadBakeSet(bakedSet()), options)->renderFrame(frame, from_exr.data());
    Runtime::open(context(), loadRuntimePack(bakedSet() + "/pack"), options)->renderFrame(frame, from_pack.data());
    EXPECT_NE(from_exr, camera) << "the building is in view";
    // E5B9G9R9 of a value decoded from E5B9G9R9 is the same texel, so the GPU holds the same lightmaps.
    EXPECT_EQ(from_pack, from_exr);
}

// The one-line message loading `folder` gives, checked to come back the same through the C API.
std::string refusal(const std::string& folder) {
    std::string message;
    try {
        loadRuntimePack(folder);
    } catch (const InputError& error) {
        message = error.what();
    }
    gusuku_bakeset* bake_set = nullptr;
    EXPECT_EQ(gusuku_bakeset_load_pack(folder.c_str(), &bake_set), GUSUKU_ERROR_INVALID_BAKE_SET) << folder;
    EXPECT_EQ(bake_set, nullptr);
    EXPECT_EQ(std::string(gusuku_last_error_message()), "gusuku_bakeset_load_pack: " + message);
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
}

std::string firstLightmap(const std::string& pack) {
    for (const auto& entry : fs::directory_iterator(pack)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("building_", 0) == 0 && name.find("_valid") == std::string::npos &&
            name.find("_astc") == std::string::npos)
            return entry.path().string();
    }
    return "";
}

TEST_F(RuntimePackTest, EveryBadFileIsRefusedNamingTheFileAndField) {
    auto expectStart = [](const std::string& message, const std::string& prefix) {
        EXPECT_EQ(message.rfind(prefix, 0), 0u) << message << "\n  expected to start with: " << prefix;
    };
    {
        const std::string pack = packCopy("truncated"), lightmap = firstLightmap(pack);
        std::vector<uint8_t> bytes = readBytes(lightmap);
        bytes.resize(bytes.size() - 100);
        writeBytes(lightmap, bytes);
        expectStart(refusal(pack), lightmap + ": levels[0]: bytes");
    }
    {
        const std::string pack = packCopy("format"), lightmap = firstLightmap(pack);
        fs::copy_file(pack + "/ground_geometry.ktx2", lightmap, fs::copy_options::overwrite_existing);
        expectStart(refusal(pack), lightmap + ": vkFormat: VK_FORMAT_R32G32B32A32_SFLOAT is not VK_FORMAT_E5B9G9R9_UFLOAT_PACK32");
    }
    {
        const std::string pack = packCopy("size");
        writeBytes(pack + "/ground_geometry.ktx2",
                   encodeKtx2({Ktx2Format::kR32g32b32a32Sfloat, 3, 3, std::vector<uint8_t>(3 * 3 * 16)}));
        expectStart(refusal(pack), pack + "/ground_geometry.ktx2: pixelWidth/pixelHeight: 3 x 3 is not the manifest's");
    }
    {
        const std::string pack = packCopy("levels"), lightmap = firstLightmap(pack);
        std::vector<uint8_t> bytes = readBytes(lightmap);
        const uint64_t length = 12;  // levels[0].byteLength at byte 88
        std::memcpy(bytes.data() + 88, &length, 8);
        writeBytes(lightmap, bytes);
        expectStart(refusal(pack), lightmap + ": levels[0].byteLength: 12 is not");
    }
    {
        const std::string pack = packCopy("valid"), lightmap = firstLightmap(pack);
        const std::string valid = lightmap.substr(0, lightmap.size() - 5) + "_valid.ktx2";
        std::vector<uint8_t> bytes = readBytes(valid);
        bytes[bytes.size() - 1] = 7;  // the last texel
        writeBytes(valid, bytes);
        expectStart(refusal(pack), valid + ": texel (");
        fs::remove(valid);
        expectStart(refusal(pack), valid + ": is missing or not a regular file");
    }
    {
        const std::string pack = packCopy("geometry");
        std::vector<uint8_t> bytes = readBytes(pack + "/pack.bin");
        bytes.resize(bytes.size() - 4);
        writeBytes(pack + "/pack.bin", bytes);
        expectStart(refusal(pack), pack + "/pack.bin: counts: their arrays take");
        bytes.resize(20);
        writeBytes(pack + "/pack.bin", bytes);
        expectStart(refusal(pack), pack + "/pack.bin: header: the file has 20 bytes");
    }
    {
        const std::string pack = packCopy("manifest");
        std::vector<uint8_t> bytes = readBytes(pack + "/manifest.json");
        const std::string text(bytes.begin(), bytes.end());
        const size_t format = text.find("gusuku-bakeset/1");
        ASSERT_NE(format, std::string::npos);
        bytes[format + 15] = '9';
        writeBytes(pack + "/manifest.json", bytes);
        expectStart(refusal(pack), pack + "/manifest.json: /format: \"gusuku-bakeset/9\" is not gusuku-bakeset/1");
        bytes.resize(bytes.size() / 2);
        writeBytes(pack + "/manifest.json", bytes);
        expectStart(refusal(pack), pack + "/manifest.json: byte ");
    }
    if (!loadBakeSet(bakedSet()).building.textures.empty()) {  // the mini site's building may be untextured
        const std::string pack = packCopy("texture");
        fs::remove(pack + "/texture_0.ktx2");
        expectStart(refusal(pack), pack + "/texture_0.ktx2: is missing");
    }
    expectStart(refusal("/nonexistent-pack"), "/nonexistent-pack/manifest.json: is missing");
}

}  // namespace
}  // namespace gusuku
