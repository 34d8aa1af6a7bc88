// Uploading a bake set to the GPU once, when the runtime opens (see runtime_scene.h).

#include "runtime_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <string>
#include <utility>

#include <glm/common.hpp>
#include <glm/gtc/packing.hpp>

#include "gusuku/maths/shared_exponent.h"
#include "gusuku/maths/srgb_mip_chain.h"
#include "gusuku/maths/texture_coverage.h"
#include "ground_quads.h"
#include "lightmap_format_choice.h"

namespace gusuku::runtime_detail {
namespace {

// Half floats hold up to 65504: irradiance above this fraction of it is stored scaled down.
constexpr float kLargestStoredHalf = 30000.0f;
// A ground term's change is relative to E_without, but never to less than this (unlit cells: no division by 0).
constexpr float kSmallestRelativeTo = 1e-6f;
constexpr VkBufferUsageFlags kVertexUsage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
constexpr VkBufferUsageFlags kIndexUsage = VK_BUFFER_USAGE_INDEX_BUFFER_BIT;

template <typename T>
GpuBuffer deviceBuffer(const GpuDevice& gpu, const std::vector<T>& values, VkBufferUsageFlags usage) {
    GpuBuffer buffer(gpu, std::max<size_t>(values.size() * sizeof(T), kMinBufferBytes), usage,
                     GpuMemory::kDeviceLocal);
    if (!values.empty()) buffer.upload(values.data(), values.size() * sizeof(T));
    return buffer;
}

float largestRgb(const BakeSetImage& image) {
    float largest = 0.0f;
    for (size_t texel = 0; texel + 3 < image.rgba.size(); texel += 4)
        largest = std::max({largest, image.rgba[texel], image.rgba[texel + 1], image.rgba[texel + 2]});
    return largest;
}

std::vector<uint16_t> toHalf(const BakeSetImage& image, float inverse_scale) {
    std::vector<uint16_t> halves(image.rgba.size());
    for (size_t index = 0; index < image.rgba.size(); ++index) {
        const bool alpha = index % 4 == 3;
        halves[index] = uint16_t(glm::packHalf1x16(alpha ? image.rgba[index] : image.rgba[index] * inverse_scale));
    }
    return halves;
}

void extend(glm::dvec3& low, glm::dvec3& high, const glm::dvec3& point) {
    low = glm::min(low, point);
    high = glm::max(high, point);
}

// The building's vertices, and its indices grouped by material so each material is one draw; its bounds.
void uploadBuilding(const GpuDevice& gpu, const BakeSetMesh& mesh, GpuScene& scene) {
    std::vector<BuildingVertex> vertices(mesh.positions.size());
    scene.building_min = glm::dvec3(INFINITY);
    scene.building_max = glm::dvec3(-INFINITY);
    for (size_t vertex = 0; vertex < vertices.size(); ++vertex) {
        BuildingVertex& out = vertices[vertex];
        const glm::vec3& position = mesh.positions[vertex];
        const glm::vec3 normal = vertex < mesh.normals.size() ? mesh.normals[vertex] : glm::vec3(0, 0, 1);
        const glm::vec2 uv0 = vertex < mesh.uv0.size() ? mesh.uv0[vertex] : glm::vec2(0.0f);
        const glm::vec2 uv1 = vertex < mesh.uv1.size() ? mesh.uv1[vertex] : glm::vec2(0.0f);
        out = {{position.x, position.y, position.z}, {normal.x, normal.y, normal.z}, {uv0.x, uv0.y}, {uv1.x, uv1.y}};
        extend(scene.building_min, scene.building_max, glm::dvec3(position));
    }
    const size_t triangle_count = mesh.indices.size() / 3;
    std::vector<uint32_t> order(triangle_count);
    std::iota(order.begin(), order.end(), 0u);
    auto materialOf = [&](uint32_t triangle) {
        return triangle < mesh.triangle_material.size() ? mesh.triangle_material[triangle] : 0u;
    };
    // Opaque materials first (issue 21 item 3), so the shadow pass draws them all at once without an alpha test.
    auto maskedOf = [&](uint32_t triangle) {
        const uint32_t material = materialOf(triangle);
        return material < mesh.materials.size() && mesh.materials[material].alpha_masked;
    };
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return std::make_pair(maskedOf(a), materialOf(a)) < std::make_pair(maskedOf(b), materialOf(b));
    });
    std::vector<uint32_t> indices;
    indices.reserve(mesh.indices.size());
    for (uint32_t triangle : order) {
        const uint32_t material = materialOf(triangle);
        if (scene.draws.empty() || scene.draws.back().material != material)
            scene.draws.push_back({uint32_t(indices.size()), 0, material});
        for (int corner = 0; corner < 3; ++corner) indices.push_back(mesh.indices[size_t(triangle) * 3 + corner]);
        scene.draws.back().index_count += 3;
        if (!maskedOf(triangle)) scene.opaque_index_count = uint32_t(indices.size());
    }
    scene.building_vertices = deviceBuffer(gpu, vertices, kVertexUsage);
    scene.building_indices = deviceBuffer(gpu, indices, kIndexUsage);
    scene.building_index_count = uint32_t(indices.size());
}

// Materials and their textures (sRGB: the sampler decodes to linear), and the white texture of untextured ones.
void uploadMaterials(const GpuDevice& gpu, const BakeSetMesh& mesh, bool astc_textures, GpuScene& scene) {
    for (const BakeSetMaterial& material : mesh.materials) {
        scene.base_colour_factors.push_back(material.base_color_factor);
        scene.material_texture.push_back(material.base_color_texture);
        scene.alpha_cutoffs.push_back(material.alpha_masked ? material.alpha_cutoff : -1.0f);
    }
    if (scene.base_colour_factors.empty()) {
        scene.base_colour_factors.push_back(glm::vec4(1.0f));
        scene.material_texture.push_back(-1);
        scene.alpha_cutoffs.push_back(-1.0f);
    }
    const MipChainMaker maker =
        canBlitMipChain(gpu, VK_FORMAT_R8G8B8A8_SRGB) ? MipChainMaker::kGpuBlit : MipChainMaker::kCpuBoxFilter;
    // A texture that an alpha-masked material reads keeps its coverage at that material's cutoff down its chain
    // (the bake's ASTC chains keep it by the same rule).
    const std::vector<float> coverage_alpha = textureCoverageAlphas(mesh);
    for (size_t texture = 0; texture < mesh.textures.size(); ++texture) {
        const BakeSetTexture& source = mesh.textures[texture];
        if (astc_textures && !source.astc6x6_levels.empty()) {
            scene.textures.push_back(uploadAstcBaseColourTexture(gpu, source));
            ++scene.astc_texture_count;
            continue;
        }
        if (source.rgba8.empty())
            throw RuntimeError(RuntimeErrorCode::kInvalidBakeSet,
                               "bake set: building.textures[" + std::to_string(texture) +
                                   "]: held only as ASTC 6x6 blocks (its RGBA8 file left out of the pack), which "
                                   "this runtime cannot draw: enable textureCompressionASTC_LDR on a device that "
                                   "has it and set options.texture_compression_astc_ldr, or ship the RGBA8 file");
        scene.textures.push_back(uploadBaseColourTexture(gpu, source, maker, coverage_alpha[texture]));
    }
    // One texel: no chain to make, and it reads white at every level of detail.
    GpuImageDescription description;
    description.format = VK_FORMAT_R8G8B8A8_SRGB;
    scene.white_texture = GpuImage(gpu, description);
    const uint8_t white[4] = {255, 255, 255, 255};
    scene.white_texture.upload(white, sizeof white, 0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

// The occluder (depth only); the casters' bounds are the building's and its.
void uploadOccluder(const GpuDevice& gpu, const BakeSetOccluder& occluder, GpuScene& scene) {
    scene.casters_min = scene.building_min;
    scene.casters_max = scene.building_max;
    scene.occluder_vertices = deviceBuffer(gpu, occluder.positions, kVertexUsage);
    scene.occluder_indices = deviceBuffer(gpu, occluder.indices, kIndexUsage);
    scene.occluder_index_count = uint32_t(occluder.indices.size());
    for (const glm::vec3& position : occluder.positions)
        extend(scene.casters_min, scene.casters_max, glm::dvec3(position));
}

// Each slot's mean E_ind over the building's valid texels: direct-only's ambient estimate.
std::vector<glm::vec3> slotMeanIndirect(const std::vector<BakeSetSlotImages>& slots) {
    std::vector<glm::vec3> means;
    for (const BakeSetSlotImages& slot : slots) {
        glm::dvec3 sum(0.0);
        double count = 0.0;
        for (size_t texel = 0; texel + 3 < slot.building.rgba.size(); texel += 4)
            if (slot.building.rgba[texel + 3] > 0.0f) {
                sum += glm::dvec3(slot.building.rgba[texel], slot.building.rgba[texel + 1], slot.building.rgba[texel + 2]);
                count += 1.0;
            }
        means.push_back(count > 0.0 ? glm::vec3(sum / count) : glm::vec3(0.0f));
    }
    return means;
}

}  // namespace

float irradianceScaleOf(const std::vector<BakeSetSlotImages>& slots) {
    float largest = 0.0f;
    for (const BakeSetSlotImages& slot : slots)
        largest = std::max({largest, largestRgb(slot.building), largestRgb(slot.ground_with),
                            largestRgb(slot.ground_without)});
    return largest > kLargestStoredHalf ? largest / kLargestStoredHalf : 1.0f;
}

namespace {

// One slot's lightmap RGB / irradiance scale in the texel layout of `codec` (a texel format's: the block formats
// come from the bake; alpha, the bake set's validity, is not read by the shaders: 1 in the 16- and 32-bit
// formats, absent in E5B9G9R9).
std::vector<uint8_t> lightmapTexels(const BakeSetImage& image, float inverse_scale, formats::TexelCodec codec) {
    const size_t texels = image.rgba.size() / 4;
    const float* rgba = image.rgba.data();
    std::vector<uint8_t> bytes;
    if (codec == formats::TexelCodec::kSharedExponent) {
        bytes.resize(texels * 4);
        for (size_t texel = 0; texel < texels; ++texel) {
            const uint32_t packed = packE5b9g9r9(rgba[texel * 4] * inverse_scale, rgba[texel * 4 + 1] * inverse_scale,
                                                 rgba[texel * 4 + 2] * inverse_scale);
            std::memcpy(&bytes[texel * 4], &packed, 4);
        }
    } else if (codec == formats::TexelCodec::kHalfFloat) {
        const std::vector<uint16_t> halves = toHalf(image, inverse_scale);
        bytes.resize(halves.size() * 2);
        std::memcpy(bytes.data(), halves.data(), bytes.size());
    } else {
        std::vector<float> floats(image.rgba.size());
        for (size_t index = 0; index < floats.size(); ++index)
            floats[index] = index % 4 == 3 ? rgba[index] : rgba[index] * inverse_scale;
        bytes.resize(floats.size() * 4);
        std::memcpy(bytes.data(), floats.data(), bytes.size());
    }
    return bytes;
}

// The lightmaps as one array, a layer per slot, in the option's format (E5B9G9R9 by default: 4 bytes a texel,
// half of RGBA16F's, docs/runtime.md "Lightmap formats" has what it costs in colour). One mip level, sampled
// bilinearly, as measured (docs/runtime.md, "Textures"): at the default 8 texels a metre a texel covers a pixel or
// more out to about 125 m at a 1000-pixel focal length, so there is nothing to alias; a trilinear chain only
// blurred obliquely seen faces and face edges (the isotropic level follows the foreshortened axis; coarse levels
// mix neighbouring charts) and made the building pass 14-16 % slower on lavapipe.
void uploadLightmaps(const GpuDevice& gpu, const BakeSetData& bake_set, float inverse_scale, LightmapFormat format,
                     GpuScene& scene) {
    const uint32_t slot_count = uint32_t(bake_set.slots.size());
    const int resolution = bake_set.manifest.building.lightmap_resolution;
    const formats::FormatRow& row = lightmapRow(format);
    GpuImageDescription description;
    description.format = VkFormat(row.vk_format);
    description.width = uint32_t(resolution);
    description.height = uint32_t(resolution);
    description.layers = slot_count;
    description.array_view = true;
    scene.lightmaps = GpuImage(gpu, description);
    for (uint32_t slot = 0; slot < slot_count; ++slot) {
        // Blocks (ASTC) as the bake encoded them (chooseLightmapFormat made sure their scale is the runtime's).
        const std::vector<uint8_t> texels = formats::isBlockCodec(row.codec)
                                                ? bake_set.slots[slot].building_blocks.at(row.vk_format)
                                                : lightmapTexels(bake_set.slots[slot].building, inverse_scale, row.codec);
        scene.lightmaps.upload(texels.data(), texels.size(), slot, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }
}

// The building's sun horizons as a 2-layer RGBA8 UNORM array, sampled bilinearly with the lightmap's coordinates
// (the horizon between texels, so a groove's shadow edge falls between them); a 1 x 1 array of open horizons for
// a bake set without them, which the shader takes for none (hasSunHorizons: a bake set's are at least 2 x 2).
void uploadSunHorizon(const GpuDevice& gpu, const BakeSetSunHorizon& horizon, GpuScene& scene) {
    GpuImageDescription description;
    description.format = VK_FORMAT_R8G8B8A8_UNORM;
    description.width = uint32_t(horizon.empty() ? 1 : horizon.width);
    description.height = uint32_t(horizon.empty() ? 1 : horizon.height);
    description.layers = kSunHorizonLayers;
    description.array_view = true;
    scene.sun_horizon = GpuImage(gpu, description);
    const size_t layer_bytes = size_t(description.width) * description.height * 4;
    const std::vector<uint8_t> open(layer_bytes, 0);
    for (uint32_t layer = 0; layer < uint32_t(kSunHorizonLayers); ++layer)
        scene.sun_horizon.upload(horizon.empty() ? open.data() : horizon.rgba8.data() + layer * layer_bytes,
                                 layer_bytes, layer, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

// The CPU's copy of the ground cells (GpuScene::ground_cell_state and ground_cell_height), and slot 0's
// E_with as half floats with layer 0's alpha marking (2) the cells where the building changes the baked light
// in any slot by more than change_threshold: elsewhere only the building's shadow can change the pixel.
std::vector<uint16_t> classifyGroundCells(const BakeSetData& bake_set, size_t cells, float change_threshold,
                                          float inverse_scale, GpuScene& scene) {
    std::vector<uint16_t> flagged = toHalf(bake_set.slots[0].ground_with, inverse_scale);
    scene.ground_cell_state.assign(cells, kCellNoGround);
    scene.ground_cell_height.assign(cells, 0.0f);
    scene.ground_cell_normal.assign(cells, glm::vec3(0.0f));
    for (size_t cell = 0; cell < cells; ++cell) {
        scene.ground_cell_height[cell] = bake_set.ground_geometry.rgba[cell * 4 + 3];
        scene.ground_cell_normal[cell] = glm::vec3(bake_set.ground_geometry.rgba[cell * 4],
                                                   bake_set.ground_geometry.rgba[cell * 4 + 1],
                                                   bake_set.ground_geometry.rgba[cell * 4 + 2]);
        if (bake_set.slots[0].ground_with.rgba[cell * 4 + 3] > 0.0f) scene.ground_cell_state[cell] = kCellGround;
        bool changed = false;
        for (const BakeSetSlotImages& slot : bake_set.slots)
            for (int channel = 0; channel < 3 && !changed; ++channel) {
                const float with = slot.ground_with.rgba[cell * 4 + channel];
                const float without = slot.ground_without.rgba[cell * 4 + channel];
                changed = std::abs(with - without) > change_threshold * std::max(without, kSmallestRelativeTo);
            }
        if (changed && scene.ground_cell_state[cell] == kCellGround) {
            flagged[cell * 4 + 3] = uint16_t(glm::packHalf1x16(float(kCellGroundChangedByBuilding)));
            scene.ground_cell_state[cell] = kCellGroundChangedByBuilding;
        }
    }
    return flagged;
}

// The ground terms as one half-float array: layers 2 slot (with the building) and 2 slot + 1 (without); zeros
// without ground.
void uploadGroundIrradiance(const GpuDevice& gpu, const BakeSetData& bake_set, uint32_t columns, uint32_t rows,
                            bool has_ground, float change_threshold, float inverse_scale, GpuScene& scene) {
    const uint32_t slot_count = uint32_t(bake_set.slots.size());
    GpuImageDescription description;
    description.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    description.width = columns;
    description.height = rows;
    description.layers = std::max(2 * slot_count, 1u);
    description.array_view = true;
    scene.ground_irradiance = GpuImage(gpu, description);
    if (!has_ground) {
        const std::vector<uint16_t> zeros(size_t(columns) * rows * 4, 0);
        for (uint32_t layer = 0; layer < description.layers; ++layer)
            scene.ground_irradiance.upload(zeros.data(), zeros.size() * 2, layer,
                                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        return;
    }
    const std::vector<uint16_t> flagged =
        classifyGroundCells(bake_set, size_t(columns) * rows, change_threshold, inverse_scale, scene);
    std::vector<std::span<const float>> with_rgba, without_rgba;
    for (const BakeSetSlotImages& slot : bake_set.slots)
        with_rgba.emplace_back(slot.ground_with.rgba), without_rgba.emplace_back(slot.ground_without.rgba);
    scene.ground_slot_light = groundSlotLight(with_rgba, without_rgba, inverse_scale);
    scene.site_heights = siteHeightTiles(bake_set.manifest.ground_grid.grid, bake_set.occluder.positions,
                                         bake_set.occluder.indices);
    for (uint32_t slot = 0; slot < slot_count; ++slot) {
        const std::vector<uint16_t> with =
            slot == 0 ? flagged : toHalf(bake_set.slots[slot].ground_with, inverse_scale);
        const std::vector<uint16_t> without = toHalf(bake_set.slots[slot].ground_without, inverse_scale);
        scene.ground_irradiance.upload(with.data(), with.size() * 2, 2 * slot,
                                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        scene.ground_irradiance.upload(without.data(), without.size() * 2, 2 * slot + 1,
                                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }
}

// The ground's normals and heights (one texel of zeros without ground).
void uploadGroundGeometry(const GpuDevice& gpu, const BakeSetData& bake_set, uint32_t columns, uint32_t rows,
                          bool has_ground, GpuScene& scene) {
    GpuImageDescription description;
    description.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    description.width = columns;
    description.height = rows;
    scene.ground_geometry = GpuImage(gpu, description);
    std::vector<float> geometry = has_ground ? bake_set.ground_geometry.rgba : std::vector<float>(4, 0.0f);
    scene.ground_geometry.upload(geometry.data(), geometry.size() * sizeof(float), 0,
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

// The receivers' bounds: the building's, and the ground grid's cells with ground between their lowest and
// highest heights.
void boundReceivers(const BakeSetData& bake_set, uint32_t columns, uint32_t rows, bool has_ground,
                    GpuScene& scene) {
    scene.receivers_min = scene.building_min;
    scene.receivers_max = scene.building_max;
    if (!has_ground) return;
    const GroundGrid& grid = bake_set.manifest.ground_grid.grid;
    double low_height = INFINITY, high_height = -INFINITY;
    for (size_t texel = 0; texel < size_t(columns) * rows; ++texel) {
        if (bake_set.slots.empty() || bake_set.slots[0].ground_with.rgba[texel * 4 + 3] <= 0.0f) continue;
        low_height = std::min(low_height, double(bake_set.ground_geometry.rgba[texel * 4 + 3]));
        high_height = std::max(high_height, double(bake_set.ground_geometry.rgba[texel * 4 + 3]));
    }
    if (low_height <= high_height) {
        extend(scene.receivers_min, scene.receivers_max, glm::dvec3(grid.origin_enu_m, low_height));
        extend(scene.receivers_min, scene.receivers_max,
               glm::dvec3(grid.origin_enu_m + glm::dvec2(grid.columns, grid.rows) * grid.cell_m, high_height));
    }
}

}  // namespace

GpuImage uploadBaseColourTexture(const GpuDevice& gpu, const BakeSetTexture& texture, MipChainMaker maker,
                                 float coverage_alpha) {
    GpuImageDescription description;
    description.format = VK_FORMAT_R8G8B8A8_SRGB;
    description.width = uint32_t(texture.width);
    description.height = uint32_t(texture.height);
    description.mip_levels = fullMipLevelCount(description.width, description.height);
    description.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    GpuImage image(gpu, description);
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    image.upload(texture.rgba8.data(), texture.rgba8.size(), 0, read);
    if (maker == MipChainMaker::kGpuBlit && !keepsAlphaCoverage(coverage_alpha)) {
        image.generateMipChain(read);
        return image;
    }
    const std::vector<std::vector<uint8_t>> levels = boxFilteredSrgbMipLevels(
        texture.rgba8.data(), description.width, description.height, description.mip_levels, coverage_alpha);
    for (size_t level = 0; level < levels.size(); ++level)
        image.upload(levels[level].data(), levels[level].size(), 0, read, uint32_t(level + 1));
    return image;
}

GpuImage uploadAstcBaseColourTexture(const GpuDevice& gpu, const BakeSetTexture& texture) {
    GpuImageDescription description;
    description.format = VK_FORMAT_ASTC_6x6_SRGB_BLOCK;
    description.width = uint32_t(texture.width);
    description.height = uint32_t(texture.height);
    description.mip_levels = uint32_t(texture.astc6x6_levels.size());
    description.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    GpuImage image(gpu, description);
    for (uint32_t level = 0; level < description.mip_levels; ++level)
        image.upload(texture.astc6x6_levels[level].data(), texture.astc6x6_levels[level].size(), 0,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, level);
    return image;
}

bool deviceSamplesAstcLdr(const GpuDevice& gpu) {
    return deviceSamples(gpu, *formats::findFormat(formats::kVkAstc6x6Srgb));
}

VkFormat lightmapVkFormat(LightmapFormat format) { return VkFormat(lightmapRow(format).vk_format); }

const char* lightmapFormatName(LightmapFormat format) {
    return lightmapRow(format).vk_name + (sizeof "VK_FORMAT_" - 1);  // "E5B9G9R9_UFLOAT_PACK32"
}

GpuScene uploadScene(const GpuDevice& gpu, const BakeSetData& bake_set, float change_threshold,
                     LightmapFormat lightmap_format, bool astc_textures) {
    GpuScene scene;
    uploadBuilding(gpu, bake_set.building, scene);
    uploadMaterials(gpu, bake_set.building, astc_textures, scene);
    uploadOccluder(gpu, bake_set.occluder, scene);
    scene.slot_mean_indirect = slotMeanIndirect(bake_set.slots);

    // Lightmaps and ground terms scaled so the largest value fits a half float (and E5B9G9R9, whose largest is
    // about the same: 65408).
    scene.irradiance_scale = irradianceScaleOf(bake_set.slots);
    const float inverse_scale = 1.0f / scene.irradiance_scale;
    uploadLightmaps(gpu, bake_set, inverse_scale, lightmap_format, scene);
    uploadSunHorizon(gpu, bake_set.building_sun_horizon, scene);
    const GroundGrid& grid = bake_set.manifest.ground_grid.grid;
    const uint32_t columns = uint32_t(std::max(grid.columns, 1)), rows = uint32_t(std::max(grid.rows, 1));
    const bool has_ground = grid.columns > 0 && grid.rows > 0 && !bake_set.ground_geometry.rgba.empty();
    uploadGroundIrradiance(gpu, bake_set, columns, rows, has_ground, change_threshold, inverse_scale, scene);
    uploadGroundGeometry(gpu, bake_set, columns, rows, has_ground, scene);

    // The ground grid's quads, one per square of four neighbouring cell centres (two triangles): each frame
    // slot has room for all of them (RuntimeImpl::createTargets) and draws those it chooses.
    scene.ground_quad_capacity = has_ground ? (columns - 1) * (rows - 1) : 0;
    boundReceivers(bake_set, columns, rows, has_ground, scene);
    glm::dvec3 all_min = glm::min(scene.receivers_min, scene.casters_min);
    glm::dvec3 all_max = glm::max(scene.receivers_max, scene.casters_max);
    scene.scene_radius_m = std::max(0.5 * glm::length(all_max - all_min), 1.0);
    return scene;
}

}  // namespace gusuku::runtime_detail
