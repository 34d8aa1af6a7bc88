// The runtime pack's ASTC HDR lightmaps, 4x4 and 6x6 (docs/runtime.md, "Lightmap formats"; every lightmap row of
// gusuku/formats/format_table.h with a pack file) on a real bake of the mini site: `gusuku-bake pack` writes
// building_<slot>_astc.ktx2 and _astc6x6.ktx2 beside the E5B9G9R9 file, each header as the KTX 2.0
// specification says (read here by hand); loadRuntimePack (standard library only) carries the blocks as they are;
// astcenc decodes them to the EXR lightmap within ASTC's error; bad or partial ASTC files are refused in one line;
// and the runtime takes E5B9G9R9 wherever the device cannot sample ASTC HDR (lavapipe), saying so, and refuses a
// forced ASTC it cannot honour. (Drawing the blocks needs a device with textureCompressionASTC_HDR, which the
// test machines lack: the composite's error is measured from decoded blocks by gusuku-lightmap-formats.)

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake_command.h"
#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/site.h"
#include "gusuku/pack_loader/runtime_pack.h"
#include "gusuku/formats/format_table.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku_bake/astc_lightmap.h"
#include "gusuku_bake/bake_job.h"
#include "mini_site.h"

namespace gusuku {
namespace {

namespace fs = std::filesystem;

// The lightmap rows the pack carries blocks of (ASTC 4x4 HDR, ASTC 6x6 HDR).
std::vector<const formats::FormatRow*> packedBlockRows() {
    std::vector<const formats::FormatRow*> rows;
    for (const formats::FormatRow& row : formats::kFormatRows)
        if (row.pack_suffix != nullptr) rows.push_back(&row);
    return rows;
}

std::vector<uint8_t> readBytes(const std::string& path) {
    std::ifstream stream(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(stream), {});
}
void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}
uint32_t u32At(const std::vector<uint8_t>& bytes, size_t at) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;
}
uint64_t u64At(const std::vector<uint8_t>& bytes, size_t at) {
    uint64_t value = 0;
    std::memcpy(&value, bytes.data() + at, 8);
    return value;
}

class RuntimePackAstcTest : public testing::GpuTest {
protected:
    static const std::string& bakedSet() { return folder_; }

    void SetUp() override {
        GpuTest::SetUp();
        if (!folder_.empty()) return;
        const std::string dir = testing::makeTemporaryDirectory("gusuku-pack-astc");
        testing::MiniSiteOptions site_options;
        site_options.samples_per_texel = 2;
        bake::BakeOptions options;
        options.output_dir = dir + "/bakeset";
        options.show_progress = false;
        ASSERT_TRUE(bake::runBake(context(), loadSiteConfig(testing::writeMiniSite(dir, site_options)), options).completed);
        const testing::CommandResult packed = testing::runBakeCommand({"pack", options.output_dir}, dir);
        ASSERT_EQ(packed.exit_code, 0) << packed.stderr_text;
        EXPECT_NE(packed.stdout_text.find("astc 4x4 hdr"), std::string::npos) << packed.stdout_text;
        EXPECT_NE(packed.stdout_text.find("astc 6x6 hdr"), std::string::npos) << packed.stdout_text;
        folder_ = options.output_dir;
    }

    std::string packCopy(const std::string& name) {
        const std::string copy = testing::makeTemporaryDirectory("gusuku-pack-astc-" + name) + "/pack";
        fs::copy(bakedSet() + "/pack", copy);
        return copy;
    }

    // The pack's block file of slot `slot` in the row's format (the manifest's building_irradiance, .exr ->
    // _astc.ktx2 for ASTC 4x4 HDR).
    std::string astcFile(const std::string& pack, size_t slot, const char* suffix = "_astc") {
        const std::string exr = loadBakeSet(bakedSet()).manifest.slots[slot].building_irradiance;
        return pack + "/" + exr.substr(0, exr.rfind('.')) + suffix + ".ktx2";
    }

    static std::string folder_;
};
std::string RuntimePackAstcTest::folder_;

TEST_F(RuntimePackAstcTest, EachSlotsAstcFileHoldsItsLightmapsBlocksAsTheSpecificationLaysThemOut) {
    const BakeSetData exr = loadBakeSet(bakedSet());
    const BakeSetData pack = loadRuntimePack(bakedSet());
    const uint32_t side = uint32_t(exr.manifest.building.lightmap_resolution);
    EXPECT_EQ(pack.building_blocks_scale, 1.0f);  // the mini site's light is far below 65408
    // Known values, not the table's: VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK and _6x6_ (vulkan_core.h), 4 and 6 texels.
    const std::vector<std::pair<uint32_t, uint32_t>> formats_and_sides = {{1000066000u, 4}, {1000066004u, 6}};
    ASSERT_EQ(packedBlockRows().size(), formats_and_sides.size());
    for (size_t index = 0; index < formats_and_sides.size(); ++index)
    for (size_t slot = 0; slot < exr.slots.size(); ++slot) {
        const auto [vk_format, block_side] = formats_and_sides[index];
        SCOPED_TRACE(std::string(packedBlockRows()[index]->name) + ", slot " + std::to_string(slot));
        const uint64_t blocks_bytes = uint64_t((side + block_side - 1) / block_side) *
                                      ((side + block_side - 1) / block_side) * 16;
        const std::vector<uint8_t> file =
            readBytes(astcFile(bakedSet() + "/pack", slot, packedBlockRows()[index]->pack_suffix));
        ASSERT_GE(file.size(), 124u);
        EXPECT_EQ(u32At(file, 12), vk_format);
        EXPECT_EQ(u32At(file, 16), 1u);           // typeSize
        EXPECT_EQ(u32At(file, 20), side);         // pixelWidth, pixelHeight: the lightmap's, in texels
        EXPECT_EQ(u32At(file, 24), side);
        EXPECT_EQ(u32At(file, 40), 1u);           // levelCount: one level (no mips)
        EXPECT_EQ(u32At(file, 116) & 0xFFu, 162u);  // DFD colour model KHR_DF_MODEL_ASTC
        EXPECT_EQ(u32At(file, 120), (block_side - 1) | (block_side - 1) << 8);  // texelBlockDimension0, 1
        const uint64_t offset = u64At(file, 80), length = u64At(file, 88);
        EXPECT_EQ(length, blocks_bytes);
        ASSERT_EQ(file.size(), offset + length);
        // The loader carries the blocks as they are.
        EXPECT_EQ(pack.slots[slot].building_blocks.at(vk_format),
                  std::vector<uint8_t>(file.begin() + long(offset), file.end()));
    }
}

TEST_F(RuntimePackAstcTest, ThePacksBlocksDecodeToTheExrLightmapsWithinAstcsError) {
    const BakeSetData exr = loadBakeSet(bakedSet());
    const BakeSetData pack = loadRuntimePack(bakedSet());
    const int side = exr.manifest.building.lightmap_resolution;
    for (const formats::FormatRow* row : packedBlockRows())
    for (size_t slot = 0; slot < exr.slots.size(); ++slot) {
        SCOPED_TRACE(std::string(row->name) + ", slot " + std::to_string(slot));
        const int b = int(row->block_side);
        const BakeSetImage decoded =
            bake::decodeAstcLightmap(pack.slots[slot].building_blocks.at(row->vk_format), side, side, row->block_side);
        const std::vector<float>& original = exr.slots[slot].building.rgba;
        // Error relative to the block's brightest channel (ASTC's endpoints are per block; a dim texel beside a
        // bright one in one block takes the block's step), over the valid texels.
        double sum = 0.0, count = 0.0, worst = 0.0;
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                const size_t texel = size_t(y) * side + x;
                if (original[texel * 4 + 3] <= 0.0f) continue;
                float block_largest = 1e-6f;
                for (int by = y / b * b; by < std::min(side, y / b * b + b); ++by)
                    for (int bx = x / b * b; bx < std::min(side, x / b * b + b); ++bx)
                        for (int channel = 0; channel < 3; ++channel)
                            block_largest = std::max(block_largest, original[(size_t(by) * side + bx) * 4 + channel]);
                for (int channel = 0; channel < 3; ++channel) {
                    const double error =
                        std::abs(double(decoded.rgba[texel * 4 + channel]) - original[texel * 4 + channel]) / block_largest;
                    sum += error;
                    count += 1.0;
                    worst = std::max(worst, error);
                }
            }
        ASSERT_GT(count, 0.0);
        // Bounds about twice what HDR ASTC gives a smooth lightmap (test_astc_lightmap: 0.72 % mean), far below
        // a wrong decode (a swapped channel or row order gives tens of per cent).
        EXPECT_LT(sum / count, 0.02) << "slot " << slot;
        EXPECT_LT(worst, 0.25) << "slot " << slot;
    }
}

// The one-line message loading `pack` gives, or "".
std::string refusal(const std::string& pack) {
    try {
        loadRuntimePack(pack);
        return "";
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos);
        return error.what();
    }
}

TEST_F(RuntimePackAstcTest, BadOrPartialAstcFilesAreRefusedAndAPackWithoutThemStillLoads) {
    auto expectStart = [](const std::string& message, const std::string& prefix) {
        EXPECT_EQ(message.rfind(prefix, 0), 0u) << message << "\n  expected to start with: " << prefix;
    };
    const size_t slots = loadBakeSet(bakedSet()).slots.size();
    ASSERT_GE(slots, 2u);
    {
        const std::string pack = packCopy("truncated"), astc = astcFile(pack, 1);
        std::vector<uint8_t> bytes = readBytes(astc);
        bytes.resize(bytes.size() - 16);
        writeBytes(astc, bytes);
        expectStart(refusal(pack), astc + ": levels[0]: bytes");
    }
    {
        const std::string pack = packCopy("format"), astc = astcFile(pack, 0);
        const std::string e5 = astc.substr(0, astc.size() - 10) + ".ktx2";
        fs::copy_file(e5, astc, fs::copy_options::overwrite_existing);
        expectStart(refusal(pack),
                    astc + ": vkFormat: VK_FORMAT_E5B9G9R9_UFLOAT_PACK32 is not VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK");
    }
    {
        // 4x4 blocks where 6x6 belong: another format, refused by name.
        const std::string pack = packCopy("swapped"), astc6 = astcFile(pack, 0, "_astc6x6");
        fs::copy_file(astcFile(pack, 0), astc6, fs::copy_options::overwrite_existing);
        expectStart(refusal(pack),
                    astc6 + ": vkFormat: VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK is not VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK");
    }
    {
        const std::string pack = packCopy("partial");
        fs::remove(astcFile(pack, 1, "_astc6x6"));
        expectStart(refusal(pack), pack + ": bake set: slots[1].building_blocks[VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK]: "
                                          "missing, but slots[0].building_blocks has them");
        for (size_t slot = 0; slot < slots; ++slot) fs::remove(astcFile(pack, slot, "_astc6x6"));
        const BakeSetData without_6x6 = loadRuntimePack(pack);  // a pack from before the 6x6 files
        for (const BakeSetSlotImages& slot : without_6x6.slots) EXPECT_EQ(slot.building_blocks.size(), 1u);
        for (size_t slot = 0; slot < slots; ++slot) fs::remove(astcFile(pack, slot));
        const BakeSetData old_pack = loadRuntimePack(pack);  // a pack from before the ASTC files
        for (const BakeSetSlotImages& slot : old_pack.slots) EXPECT_TRUE(slot.building_blocks.empty());
    }
}

RuntimeOptions smallFrame(LightmapFormat format, bool astc_enabled) {
    RuntimeOptions options;
    options.frame_width = 64;
    options.frame_height = 48;
    options.lightmap_format = format;
    options.texture_compression_astc_hdr = astc_enabled;
    return options;
}

std::string openError(const GpuDevice& gpu, const BakeSetData& bake_set, const RuntimeOptions& options,
                      RuntimeErrorCode expected_code) {
    try {
        Runtime::open(gpu, bake_set, options);
    } catch (const RuntimeError& error) {
        EXPECT_EQ(error.code(), expected_code) << error.what();
        return error.what();
    }
    ADD_FAILURE() << "the runtime opened";
    return "";
}

TEST_F(RuntimePackAstcTest, TheRuntimeTakesE5b9g9r9WhereAstcHdrCannotBeSampledAndSaysSo) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(context().gpu().physical_device, VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK, &properties);
    if (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)
        GTEST_SKIP() << "this device samples ASTC HDR; the test's device does not enable the feature, so claiming it "
                        "would be invalid";
    const BakeSetData pack = loadRuntimePack(bakedSet());
    // kAuto (the default): E5B9G9R9 whether or not the app says it enabled the feature, and the runtime says so.
    EXPECT_EQ(RuntimeOptions{}.lightmap_format, LightmapFormat::kAuto);
    EXPECT_EQ(Runtime::open(context(), pack, smallFrame(LightmapFormat::kAuto, false))->lightmapFormat(),
              LightmapFormat::kE5b9g9r9);
    EXPECT_EQ(Runtime::open(context(), pack, smallFrame(LightmapFormat::kAuto, true))->lightmapFormat(),
              LightmapFormat::kE5b9g9r9);
    EXPECT_EQ(Runtime::openHeadless(pack, smallFrame(LightmapFormat::kAuto, true))->lightmapFormat(),
              LightmapFormat::kE5b9g9r9);
    EXPECT_EQ(Runtime::open(context(), pack, smallFrame(LightmapFormat::kRgba16f, false))->lightmapFormat(),
              LightmapFormat::kRgba16f);
    // Forced ASTC: refused without the feature, on a device that cannot sample it, and on EXRs (no blocks).
    EXPECT_NE(openError(context().gpu(), pack, smallFrame(LightmapFormat::kAstc4x4Hdr, false), RuntimeErrorCode::kDevice)
                  .find("options.texture_compression_astc_hdr is false"),
              std::string::npos);
    EXPECT_NE(openError(context().gpu(), pack, smallFrame(LightmapFormat::kAstc4x4Hdr, true), RuntimeErrorCode::kDevice)
                  .find("for ASTC_4x4_SFLOAT_BLOCK (VkFormat 1000066000, the lightmaps (options.lightmap_format))"),
              std::string::npos);
    EXPECT_NE(openError(context().gpu(), loadBakeSet(bakedSet()), smallFrame(LightmapFormat::kAstc4x4Hdr, true),
                        RuntimeErrorCode::kInvalidBakeSet)
                  .find("the bake set has no astc 4x4 hdr lightmaps"),
              std::string::npos);
    // ASTC 6x6 HDR (a row of the format table, nothing else of its own) is refused alike.
    EXPECT_NE(openError(context().gpu(), pack, smallFrame(LightmapFormat::kAstc6x6Hdr, false), RuntimeErrorCode::kDevice)
                  .find("options.lightmap_format: astc 6x6 hdr needs textureCompressionASTC_HDR"),
              std::string::npos);
    EXPECT_NE(openError(context().gpu(), pack, smallFrame(LightmapFormat::kAstc6x6Hdr, true), RuntimeErrorCode::kDevice)
                  .find("for ASTC_6x6_SFLOAT_BLOCK (VkFormat 1000066004, the lightmaps (options.lightmap_format))"),
              std::string::npos);
    EXPECT_NE(openError(context().gpu(), loadBakeSet(bakedSet()), smallFrame(LightmapFormat::kAstc6x6Hdr, true),
                        RuntimeErrorCode::kInvalidBakeSet)
                  .find("the bake set has no astc 6x6 hdr lightmaps"),
              std::string::npos);
}

}  // namespace
}  // namespace gusuku
