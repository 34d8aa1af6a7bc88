// The runtime's colour statistics pass: see colour_statistics_pass.h.
#include "colour_statistics_pass.h"
#include "memory_barrier.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "colour_statistics_comp_spv.h"
#include "colour_statistics_ground_comp_spv.h"
#include "colour_statistics_ground_reduce_comp_spv.h"
#include "colour_statistics_reduce_comp_spv.h"

namespace gusuku {

using shader_interface::ColourMatchState;
using shader_interface::ColourReducePushConstants;
using shader_interface::ColourStatisticsPartial;
using shader_interface::ColourStatisticsPushConstants;
using shader_interface::GroundMatchCellGpu;
using shader_interface::GroundMatchFrame;
using shader_interface::GroundMatchSample;
using shader_interface::SunEvidenceGroundFrame;
using shader_interface::vec3;
using shader_interface::vec4;

// std430 and C++ must agree on every offset (interface_types.h's rules).
static_assert(offsetof(ColourMatchState, source_lab_mean) == 0);
static_assert(offsetof(ColourMatchState, source_lab_sigma) == 16);
static_assert(offsetof(ColourMatchState, mode) == 32);
static_assert(offsetof(ColourMatchState, gain_limit) == 36);
static_assert(offsetof(ColourMatchState, camera_lab_mean) == 48);
static_assert(offsetof(ColourMatchState, camera_lab_variance) == 64);
static_assert(offsetof(ColourMatchState, frame_lab_mean) == 80);
static_assert(offsetof(ColourMatchState, frame_lab_sigma) == 96);
static_assert(offsetof(ColourMatchState, camera_valid) == 112);
static_assert(offsetof(ColourMatchState, frame_accepted) == 132);
static_assert(offsetof(ColourMatchState, ground_gain) == 144);
static_assert(offsetof(ColourMatchState, frame_ground_gain) == 160);
static_assert(offsetof(ColourMatchState, frame_ground_median_bin) == 172);
static_assert(offsetof(ColourMatchState, frame_ground_observed) == 176);
static_assert(offsetof(ColourMatchState, frame_ground_predicted) == 192);
static_assert(offsetof(ColourMatchState, ground_valid) == 208);
static_assert(offsetof(ColourMatchState, frame_ground_accepted) == 228);
static_assert(sizeof(ColourMatchState) == 240);
static_assert(offsetof(GroundMatchSample, bin) == 12);
static_assert(offsetof(GroundMatchSample, predicted) == 16);
static_assert(offsetof(GroundMatchSample, clipped) == 28);
static_assert(sizeof(GroundMatchSample) == 32);
static_assert(offsetof(GroundMatchCellGpu, ground) == 12);
static_assert(offsetof(GroundMatchCellGpu, normal) == 16);
static_assert(offsetof(GroundMatchCellGpu, height_m) == 28);
static_assert(sizeof(GroundMatchCellGpu) == 32);
static_assert(offsetof(GroundMatchFrame, first_plane_height_m) == 12);
static_assert(offsetof(GroundMatchFrame, ray_y) == 16);
static_assert(offsetof(GroundMatchFrame, sun_shines) == 28);
static_assert(offsetof(GroundMatchFrame, ray_z) == 32);
static_assert(offsetof(GroundMatchFrame, exposure) == 44);
static_assert(offsetof(GroundMatchFrame, camera_position) == 48);
static_assert(offsetof(GroundMatchFrame, ground_origin_east_m) == 60);
static_assert(offsetof(GroundMatchFrame, sun_direction) == 64);
static_assert(offsetof(GroundMatchFrame, ground_origin_north_m) == 76);
static_assert(offsetof(GroundMatchFrame, sun_irradiance) == 80);
static_assert(offsetof(GroundMatchFrame, ground_cell_m) == 92);
static_assert(offsetof(GroundMatchFrame, slot_weights) == 96);
static_assert(offsetof(GroundMatchFrame, slot_count) == 108);
static_assert(offsetof(GroundMatchFrame, slot_index0) == 112);
static_assert(offsetof(GroundMatchFrame, rows) == 132);
static_assert(sizeof(GroundMatchFrame) == 144);
static_assert(uint32_t(ColourMatchMode::kGround) == COLOUR_MATCH_MODE_GROUND);
static_assert(GROUND_MATCH_BINS == kGroundMatchBins);
static_assert(GROUND_MATCH_WINDOW_BINS == kGroundMatchWindowBins);
static_assert(GROUND_MATCH_HEIGHT_ITERATIONS == kGroundMatchHeightIterations);
static_assert(GROUND_MATCH_BINS_PER_STOP == kGroundMatchBinsPerStop);
static_assert(GROUND_MATCH_LOWEST_LOG2_RATIO == kGroundMatchLowestLog2Ratio);
static_assert(GROUND_MATCH_MIN_PREDICTED == kGroundMatchMinPredicted);
static_assert(COLOUR_MATCH_MAX_WHITE_BALANCE_SHIFT == kColourMatchMaxWhiteBalanceShift);
static_assert(COLOUR_MATCH_GAMUT_STEPS == kColourMatchGamutSteps);
static_assert(COLOUR_MATCH_MAX_LINEAR == kColourMatchMaxLinear);
static_assert(COLOUR_MATCH_GAMUT_TOLERANCE == kColourMatchGamutTolerance);
static_assert(offsetof(ColourStatisticsPartial, valid_count) == 12);
static_assert(offsetof(ColourStatisticsPartial, lab_m2) == 16);
static_assert(offsetof(ColourStatisticsPartial, clipped_count) == 28);
static_assert(sizeof(ColourStatisticsPartial) == 32);
static_assert(uint32_t(ColourMatchMode::kOff) == COLOUR_MATCH_MODE_OFF);
static_assert(sizeof(shader_interface::SunEvidenceGroundFrame) == SUN_EVIDENCE_SAMPLES_OFFSET);
static_assert(GROUND_MATCH_SUN_EVIDENCE_BINDING == GROUND_MATCH_BINDING_COUNT);
static_assert(uint32_t(ColourMatchMode::kReinhard) == COLOUR_MATCH_MODE_PAPER);
static_assert(uint32_t(ColourMatchMode::kPreserve) == COLOUR_MATCH_MODE_PRESERVE);

namespace {

// The host part of the state: bytes [0, kHostStateBytes), written by vkCmdUpdateBuffer.
constexpr size_t kHostStateBytes = offsetof(ColourMatchState, camera_lab_mean);

uint32_t divideRoundingUp(uint64_t value, uint32_t divisor) { return uint32_t((value + divisor - 1) / divisor); }

ColourStatisticsGrid gridOrThrow(uint32_t width, uint32_t height, uint32_t stride) {
    try {
        return colourStatisticsGrid(width, height, stride);
    } catch (const std::invalid_argument& error) {
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, error.what());
    }
}

// The device's subgroup properties, or none on a Vulkan 1.0 instance or device: vkGetPhysicalDeviceProperties2 is
// Vulkan 1.1, and an app's 1.0 instance may not call it.
std::optional<VkPhysicalDeviceSubgroupProperties> querySubgroupProperties(const GpuDevice& gpu) {
    const uint32_t device_version = gpu.properties.apiVersion;
    if (gpu.instance_api_version < VK_API_VERSION_1_1 ||
        (VK_API_VERSION_MAJOR(device_version) == 1 && VK_API_VERSION_MINOR(device_version) < 1))
        return std::nullopt;
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(gpu.physical_device, &properties);
    return subgroup;
}

bool hasSubgroupArithmetic(const std::optional<VkPhysicalDeviceSubgroupProperties>& subgroup) {
    const VkSubgroupFeatureFlags needed = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
    return subgroup && (subgroup->supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
           (subgroup->supportedOperations & needed) == needed && subgroup->subgroupSize > 0;
}

VkPhysicalDeviceSubgroupProperties subgroupPropertiesOf(const GpuDevice& gpu) {
    const std::optional<VkPhysicalDeviceSubgroupProperties> subgroup = querySubgroupProperties(gpu);
    if (!hasSubgroupArithmetic(subgroup))
        throw RuntimeError(RuntimeErrorCode::kDevice,
                           "colour statistics: the device has no subgroup arithmetic in compute shaders");
    return *subgroup;
}

bool queueFamilyHasGraphics(const GpuDevice& gpu) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(gpu.physical_device, &count, nullptr);
    // At most a handful of families; read once at construction.
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(gpu.physical_device, &count, families.data());
    return gpu.queue_family_index < count && (families[gpu.queue_family_index].queueFlags & VK_QUEUE_GRAPHICS_BIT);
}

using runtime_detail::recordMemoryBarrier;

// Before a statistics kernel (the Lab one or the ground one): the camera pixels' writers, and the earlier users
// of the state and the partials, against the kernel and its reduce.
void recordBeforeStatistics(VkCommandBuffer cmd, VkPipelineStageFlags fragment) {
    recordMemoryBarrier(cmd,
                        VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                            VK_PIPELINE_STAGE_HOST_BIT | fragment,
                        VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_HOST_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

// After a reduce: the state it wrote, to the building's fragment shader, later kernels, copies and the host.
void recordAfterReduce(VkCommandBuffer cmd, VkPipelineStageFlags fragment) {
    recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | fragment | VK_PIPELINE_STAGE_TRANSFER_BIT |
                            VK_PIPELINE_STAGE_HOST_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT);
}

ColourStatisticsPushConstants statisticsPush(uint32_t frame_width, uint32_t frame_height,
                                             const ColourStatisticsGrid& grid, uint32_t workgroups_x,
                                             uint32_t partials_per_workgroup) {
    ColourStatisticsPushConstants statistics{};
    statistics.frame_width = frame_width;
    statistics.frame_height = frame_height;
    statistics.stride = grid.stride;
    statistics.first_sample_offset = grid.offset;
    statistics.samples_x = grid.samples_x;
    statistics.samples_y = grid.samples_y;
    statistics.workgroups_x = workgroups_x;
    statistics.partials_per_workgroup = partials_per_workgroup;
    return statistics;
}

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

vec4 toVec4(const glm::dvec3& v, double w) { return {{float(v.x), float(v.y), float(v.z), float(w)}}; }

vec3 toVec3(const glm::dvec3& v) { return {{float(v.x), float(v.y), float(v.z)}}; }

std::vector<GroundMatchCellGpu> groundCellsFor(const GroundMatchScene& scene) {
    std::vector<GroundMatchCellGpu> cells(scene.cells.size());
    for (size_t i = 0; i < cells.size(); ++i) {
        const GroundMatchCell& cell = scene.cells[i];
        cells[i].albedo = toVec3(glm::dvec3(cell.albedo));
        cells[i].ground = cell.ground ? 1.0f : 0.0f;
        cells[i].normal = toVec3(glm::dvec3(cell.normal));
        cells[i].height_m = float(cell.height_m);
    }
    return cells;
}

std::vector<vec4> groundIrradianceFor(const GroundMatchScene& scene) {
    std::vector<vec4> irradiance;
    irradiance.reserve(scene.irradiance_without.size() * scene.cells.size() + 1);
    for (const std::vector<glm::vec3>& slot : scene.irradiance_without)
        for (const glm::vec3& value : slot) irradiance.push_back(toVec4(glm::dvec3(value), 0.0));
    if (irradiance.empty()) irradiance.push_back({});  // a binding needs bytes
    return irradiance;
}

}  // namespace

bool ColourStatisticsPass::deviceSupports(const GpuDevice& gpu) {
    // The ground match's kernel reads 6 storage buffers (the sun evidence's included), more than the 4 Vulkan 1.0
    // promises a stage: a device with fewer opens with the matches off, as one without subgroups does.
    return hasSubgroupArithmetic(querySubgroupProperties(gpu)) &&
           gpu.limits().maxPerStageDescriptorStorageBuffers >= GROUND_MATCH_BINDING_COUNT + 1;
}

ColourStatisticsPass::ColourStatisticsPass(const GpuDevice& gpu, uint32_t frame_width, uint32_t frame_height,
                                           uint32_t stride, float smoothing_frames, const GroundMatchScene* ground)
    : gpu_(gpu),
      frame_width_(frame_width),
      frame_height_(frame_height),
      grid_(gridOrThrow(frame_width, frame_height, stride)),
      workgroups_x_(divideRoundingUp(grid_.samples_x, COLOUR_STATISTICS_TILE)),
      workgroups_y_(divideRoundingUp(grid_.samples_y, COLOUR_STATISTICS_TILE)),
      // Without VK_EXT_subgroup_size_control, a SPIR-V 1.3 compute shader runs with subgroupSize lanes.
      partials_per_workgroup_(divideRoundingUp(COLOUR_STATISTICS_TILE * COLOUR_STATISTICS_TILE,
                                               subgroupPropertiesOf(gpu).subgroupSize)),
      min_valid_samples_(colourStatisticsMinValidSamples(grid_.sampleCount())),
      smoothing_weight_(float(colourStatisticsSmoothingWeight(smoothing_frames))),
      queue_has_graphics_(queueFamilyHasGraphics(gpu)),
      state_buffer_(gpu, sizeof(ColourMatchState), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuMemory::kHostVisible),
      partial_buffer_(gpu, size_t(workgroups_x_) * workgroups_y_ * partials_per_workgroup_ *
                               sizeof(ColourStatisticsPartial),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuMemory::kDeviceLocal),
      statistics_pipeline_(gpu, kColourStatisticsCompSpirv, sizeof kColourStatisticsCompSpirv,
                           COLOUR_STATISTICS_BINDING_COUNT, sizeof(ColourStatisticsPushConstants)),
      reduce_pipeline_(gpu, kColourStatisticsReduceCompSpirv, sizeof kColourStatisticsReduceCompSpirv,
                       COLOUR_REDUCE_BINDING_COUNT, sizeof(ColourReducePushConstants)) {
    // Mode off, no camera statistics: the transfer is the identity until the first frame.
    const ColourMatchState initial{};
    state_buffer_.upload(&initial, sizeof initial);
    reduce_pipeline_.bindBuffers({&partial_buffer_, &state_buffer_});
    if (ground == nullptr) return;
    sample_grid_ground_ = colourStatisticsGrid(frame_width, frame_height,
                                               groundMatchStride(frame_width, frame_height, grid_.stride));
    ground_workgroups_x_ = divideRoundingUp(sample_grid_ground_.samples_x, COLOUR_STATISTICS_TILE);
    ground_workgroups_y_ = divideRoundingUp(sample_grid_ground_.samples_y, COLOUR_STATISTICS_TILE);
    ground_min_samples_ = colourStatisticsMinValidSamples(sample_grid_ground_.sampleCount());
    ground_start_height_m_ = ground->start_height_m;
    ground_grid_ = ground->grid;
    ground_slot_count_ = uint32_t(ground->irradiance_without.size());
    const std::vector<GroundMatchCellGpu> cells = groundCellsFor(*ground);
    const std::vector<vec4> irradiance = groundIrradianceFor(*ground);
    ground_cell_buffer_ = GpuBuffer(gpu, cells.size() * sizeof(GroundMatchCellGpu), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    GpuMemory::kDeviceLocal);
    ground_cell_buffer_.upload(cells.data(), cells.size() * sizeof(GroundMatchCellGpu));
    ground_irradiance_buffer_ = GpuBuffer(gpu, irradiance.size() * sizeof(vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                          GpuMemory::kDeviceLocal);
    ground_irradiance_buffer_.upload(irradiance.data(), irradiance.size() * sizeof(vec4));
    // Written in the command buffer (vkCmdUpdateBuffer), not by the host: with frames in flight a host write
    // could land while an earlier frame's kernel still reads it.
    ground_frame_buffer_ = GpuBuffer(gpu, sizeof(GroundMatchFrame),
                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                     GpuMemory::kDeviceLocal);
    const GroundMatchFrame no_view{};
    ground_frame_buffer_.upload(&no_view, sizeof no_view);
    ground_partial_buffer_ = GpuBuffer(gpu, size_t(sample_grid_ground_.sampleCount()) * sizeof(GroundMatchSample),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuMemory::kDeviceLocal);
    // The sun evidence's frame (measure 0) until enableSunEvidence() gives it samples.
    ground_sun_evidence_buffer_ = GpuBuffer(gpu, sizeof(SunEvidenceGroundFrame),
                                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                            GpuMemory::kDeviceLocal);
    ground_sun_evidence_buffer_.upload(&sun_evidence_frame_, sizeof sun_evidence_frame_);
    ground_statistics_pipeline_ = std::make_unique<ComputePipeline>(
        gpu, kColourStatisticsGroundCompSpirv, sizeof kColourStatisticsGroundCompSpirv,
        GROUND_MATCH_BINDING_COUNT + 1, sizeof(ColourStatisticsPushConstants));
    ground_reduce_pipeline_ = std::make_unique<ComputePipeline>(
        gpu, kColourStatisticsGroundReduceCompSpirv, sizeof kColourStatisticsGroundReduceCompSpirv,
        GROUND_REDUCE_BINDING_COUNT, sizeof(ColourReducePushConstants));
    ground_reduce_pipeline_->bindBuffers({&ground_partial_buffer_, &state_buffer_});
}

GroundMatchFrame ColourStatisticsPass::groundFrameFor(const GroundMatchView& view) const {
    // The ray through pixel point (u, v): R ((u - cx) / fx, (v - cy) / fy, 1) = u ray_x + v ray_y + ray_z.
    GroundMatchFrame frame{};
    const glm::dvec3 axis_x = view.camera_to_enu[0] / view.fx, axis_y = view.camera_to_enu[1] / view.fy;
    frame.ray_x = toVec3(axis_x);
    frame.ray_y = toVec3(axis_y);
    frame.ray_z = toVec3(view.camera_to_enu[2] - view.cx * axis_x - view.cy * axis_y);
    frame.first_plane_height_m = ground_start_height_m_;
    frame.camera_position = toVec3(view.camera_position_enu);
    frame.sun_direction = toVec3(view.sun_direction_enu);
    frame.sun_shines = view.sun_shines ? 1u : 0u;
    frame.sun_irradiance = toVec3(view.sun_irradiance_rgb);
    frame.exposure = float(view.exposure);
    uint32_t* const slot_indices[3] = {&frame.slot_index0, &frame.slot_index1, &frame.slot_index2};
    for (int k = 0; k < 3; ++k) {
        const bool used = view.slots[k] >= 0 && uint32_t(view.slots[k]) < ground_slot_count_ && view.weights[k] > 0.0f;
        frame.slot_weights[k] = used ? view.weights[k] : 0.0f;
        *slot_indices[k] = used ? uint32_t(view.slots[k]) : 0u;
    }
    frame.ground_origin_east_m = float(ground_grid_.origin_enu_m.x);
    frame.ground_origin_north_m = float(ground_grid_.origin_enu_m.y);
    frame.ground_cell_m = float(ground_grid_.cell_m);
    frame.cell_count = uint32_t(ground_grid_.cellCount());
    frame.columns = uint32_t(ground_grid_.columns);
    frame.rows = uint32_t(ground_grid_.rows);
    frame.slot_count = ground_slot_count_;
    return frame;
}

void ColourStatisticsPass::enableSunEvidence() {
    const size_t bytes = sizeof(SunEvidenceGroundFrame) +
                         size_t(sample_grid_ground_.sampleCount()) * sizeof(shader_interface::SunEvidenceSampleGpu);
    if (!hasGround() || ground_sun_evidence_buffer_.size() >= bytes) return;
    ground_sun_evidence_buffer_ = GpuBuffer(gpu_, bytes,
                                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                            GpuMemory::kDeviceLocal);
    ground_sun_evidence_buffer_.upload(&sun_evidence_frame_, sizeof sun_evidence_frame_);
    ground_bound_camera_buffer_ = VK_NULL_HANDLE;  // the next recordGround binds the new buffer
}

void ColourStatisticsPass::requestSunEvidence(const SunEvidenceGroundFrame& frame) {
    sun_evidence_frame_ = frame;
    sun_evidence_frame_.measure = 1u;
}

void ColourStatisticsPass::recordGround(VkCommandBuffer cmd, const GpuBuffer& camera_buffer,
                                        const GroundMatchView& view) {
    if (!hasGround())
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "colour match ground: the bake set has no ground_grid.albedo (bake it again)");
    if (camera_buffer.size() < size_t(frame_width_) * frame_height_ * 4)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "colour statistics: camera buffer: " + std::to_string(camera_buffer.size()) +
                               " bytes, the frame needs " + std::to_string(size_t(frame_width_) * frame_height_ * 4));
    if (camera_buffer.handle() != ground_bound_camera_buffer_) {
        ground_statistics_pipeline_->bindBuffers({&camera_buffer, &ground_partial_buffer_, &ground_cell_buffer_,
                                                  &ground_irradiance_buffer_, &ground_frame_buffer_,
                                                  &ground_sun_evidence_buffer_});
        ground_bound_camera_buffer_ = camera_buffer.handle();
    }
    const GroundMatchFrame frame = groundFrameFor(view);
    // The earlier frames' kernels read the view before this write replaces it (write after read: execution only).
    recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, 0);
    vkCmdUpdateBuffer(cmd, ground_frame_buffer_.handle(), 0, sizeof frame, &frame);
    // The sun evidence's frame: measure 1 on this frame only when requested since the last recordGround.
    vkCmdUpdateBuffer(cmd, ground_sun_evidence_buffer_.handle(), 0, sizeof sun_evidence_frame_, &sun_evidence_frame_);
    sun_evidence_frame_.measure = 0u;

    const VkPipelineStageFlags fragment = queue_has_graphics_ ? VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT : 0;
    recordBeforeStatistics(cmd, fragment);
    const ColourStatisticsPushConstants statistics = statisticsPush(
        frame_width_, frame_height_, sample_grid_ground_, ground_workgroups_x_, GROUND_MATCH_BINS);
    ground_statistics_pipeline_->recordDispatch(cmd, &statistics, ground_workgroups_x_, ground_workgroups_y_);
    recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    ColourReducePushConstants reduce{};
    reduce.partial_count = uint32_t(sample_grid_ground_.sampleCount());
    reduce.min_valid_samples = ground_min_samples_;
    reduce.smoothing_weight = smoothing_weight_;
    reduce.reset = reset_pending_ ? 1u : 0u;
    ground_reduce_pipeline_->recordDispatch(cmd, &reduce, 1);
    reset_pending_ = false;
    recordAfterReduce(cmd, fragment);
}

void ColourStatisticsPass::recordSourceUpdate(VkCommandBuffer cmd, const LabStatistics& source, ColourMatchMode mode,
                                              float gain_limit) {
    const glm::vec3& sigma = source.standard_deviation;
    if (!isFinite(source.mean) || !isFinite(sigma) || sigma.x < 0.0f || sigma.y < 0.0f || sigma.z < 0.0f)
        throw RuntimeError(RuntimeErrorCode::kInvalidBakeSet,
                           "colour_statistics: lab_mean, lab_sigma: not finite, or a negative sigma");
    ColourMatchState host_part{};
    for (int c = 0; c < 3; ++c) {
        host_part.source_lab_mean[c] = source.mean[c];
        host_part.source_lab_sigma[c] = sigma[c];
    }
    host_part.mode = uint32_t(mode);
    host_part.gain_limit = gain_limit;
    // Earlier reads of the host part (last frame's building pass) must finish before it is overwritten.
    const VkPipelineStageFlags readers =
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | (queue_has_graphics_ ? VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT : 0);
    recordMemoryBarrier(cmd, readers, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, 0);
    vkCmdUpdateBuffer(cmd, state_buffer_.handle(), 0, kHostStateBytes, &host_part);
    recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, readers,
                        VK_ACCESS_SHADER_READ_BIT);
}

void ColourStatisticsPass::record(VkCommandBuffer cmd, const GpuBuffer& camera_buffer) {
    if (camera_buffer.size() < size_t(frame_width_) * frame_height_ * 4)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "colour statistics: camera buffer: " + std::to_string(camera_buffer.size()) +
                               " bytes, the frame needs " + std::to_string(size_t(frame_width_) * frame_height_ * 4));
    if (camera_buffer.handle() != bound_camera_buffer_) {
        statistics_pipeline_.bindBuffers({&camera_buffer, &partial_buffer_});
        bound_camera_buffer_ = camera_buffer.handle();
    }
    const VkPipelineStageFlags fragment = queue_has_graphics_ ? VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT : 0;

    // The camera pixels' writers and the state's and partials' earlier users, against both dispatches.
    recordBeforeStatistics(cmd, fragment);

    const ColourStatisticsPushConstants statistics =
        statisticsPush(frame_width_, frame_height_, grid_, workgroups_x_, partials_per_workgroup_);
    statistics_pipeline_.recordDispatch(cmd, &statistics, workgroups_x_, workgroups_y_);

    recordMemoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);

    ColourReducePushConstants reduce{};
    reduce.partial_count = workgroups_x_ * workgroups_y_ * partials_per_workgroup_;
    reduce.min_valid_samples = min_valid_samples_;
    reduce.smoothing_weight = smoothing_weight_;
    reduce.reset = reset_pending_ ? 1u : 0u;
    reduce_pipeline_.recordDispatch(cmd, &reduce, 1);
    reset_pending_ = false;

    recordAfterReduce(cmd, fragment);
}

ColourMatchState ColourStatisticsPass::readState() const {
    ColourMatchState state{};
    state_buffer_.download(&state, sizeof state);
    return state;
}

}  // namespace gusuku
