// The Vulkan context and the compute helpers on the real device (lavapipe in CI), with validation on.

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/gpu/gpu_compute.h"
#include "smoke_scale_add_comp_spv.h"

namespace gusuku {
namespace {

using testing::GpuTest;

// Mirrors the push-constant block of shaders/tests/smoke_scale_add.comp.
struct ScaleAddParams {
    float scale;
    float offset;
    uint32_t count;
};

constexpr uint32_t kWorkgroupSize = 64;  // local_size_x in the shader

class VulkanTest : public GpuTest {};

TEST_F(VulkanTest, ContextReportsADeviceWithSubgroupArithmetic) {
    const VulkanContext& vulkan = context();
    EXPECT_TRUE(vulkan.validationEnabled());
    EXPECT_NE(vulkan.device(), VK_NULL_HANDLE);
    EXPECT_NE(vulkan.queue(), VK_NULL_HANDLE);
    EXPECT_GE(vulkan.properties().apiVersion, VK_API_VERSION_1_1);
    const std::string description = vulkan.deviceDescription();
    EXPECT_NE(description.find(vulkan.properties().deviceName), std::string::npos) << description;
    EXPECT_NE(description.find("Vulkan 1."), std::string::npos) << description;
    std::cout << "device: " << description << '\n';

    const VkPhysicalDeviceSubgroupProperties& subgroup = vulkan.subgroupProperties();
    EXPECT_GE(subgroup.subgroupSize, 1u);
    EXPECT_TRUE(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT);
    EXPECT_TRUE(subgroup.supportedOperations & VK_SUBGROUP_FEATURE_ARITHMETIC_BIT);
}

TEST_F(VulkanTest, ScaleAddShaderMatchesTheCpuBitForBit) {
    // Not a multiple of the workgroup size, so the shader's range check is exercised too.
    constexpr uint32_t count = 100'003;
    std::vector<float> inputs(count);
    uint32_t lcg_state = 12345u;  // any spread of magnitudes and signs will do; an LCG keeps it reproducible
    for (float& input : inputs) {
        lcg_state = lcg_state * 1664525u + 1013904223u;
        input = (static_cast<float>(lcg_state >> 8) / 16777216.0f - 0.5f) * 2000.0f;
    }
    const ScaleAddParams params{1.7f, -0.3f, count};

    GpuBuffer input_buffer(context(), count * sizeof(float));
    GpuBuffer output_buffer(context(), count * sizeof(float));
    GpuBuffer key_sum_buffer(context(), sizeof(uint32_t));
    input_buffer.uploadVector(inputs);
    const uint32_t zero = 0;
    key_sum_buffer.upload(&zero, sizeof(zero));

    ComputePipeline pipeline(context(), kSmokeScaleAddCompSpirv, sizeof(kSmokeScaleAddCompSpirv), 3, sizeof(ScaleAddParams));
    pipeline.bindBuffers({&input_buffer, &output_buffer, &key_sum_buffer});
    pipeline.dispatchAndWait(&params, (count + kWorkgroupSize - 1) / kWorkgroupSize);

    const std::vector<float> outputs = output_buffer.downloadVector<float>(count);
    size_t mismatches = 0;
    for (uint32_t index = 0; index < count; ++index) {
        // Two roundings, as the shader's `precise` asks for (no fused multiply-add).
        const float product = params.scale * inputs[index];
        const float expected = product + params.offset;
        if (std::memcmp(&expected, &outputs[index], sizeof(float)) != 0 && ++mismatches <= 5)
            ADD_FAILURE() << "element " << index << ": input " << inputs[index] << " gave " << outputs[index]
                          << ", expected " << expected;
    }
    EXPECT_EQ(mismatches, 0u);

    // The subgroupAdd reduction: sum over i of (i % 1000) + 1, an exact integer.
    uint64_t expected_key_sum = 0;
    for (uint32_t index = 0; index < count; ++index) expected_key_sum += index % 1000u + 1u;
    ASSERT_LT(expected_key_sum, uint64_t{1} << 32);
    EXPECT_EQ(key_sum_buffer.downloadVector<uint32_t>(1)[0], expected_key_sum);
}

TEST_F(VulkanTest, InvalidApiUseIsReportedByValidation) {
    // A barrier whose source access (host write) is not done by its source stage (compute) is invalid
    // (VUID-vkCmdPipelineBarrier-srcAccessMask-02815). Chosen because lavapipe ignores access masks, so the
    // call is harmless when the layer passes it on; a dispatch with no pipeline bound is reported too, but then
    // crashes lavapipe.
    const size_t count_before = context().validationMessageCount();
    context().submitAndWait([](VkCommandBuffer cmd) {
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_HOST_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
                             &barrier, 0, nullptr, 0, nullptr);
    });
    EXPECT_GT(context().validationMessageCount(), count_before);

    // Accept the messages so that the fixture's TearDown does not fail the test, and check what they say.
    const std::vector<std::string> messages = takeValidationMessages();
    ASSERT_FALSE(messages.empty());
    bool names_the_barrier = false;
    for (const std::string& message : messages)
        names_the_barrier |= message.rfind("ERROR [", 0) == 0 && message.find("vkCmdPipelineBarrier") != std::string::npos;
    EXPECT_TRUE(names_the_barrier) << messages.front();
    EXPECT_TRUE(takeValidationMessages().empty());
}

TEST_F(VulkanTest, StorageBufferBeyondTheDeviceLimitThrows) {
    const VkDeviceSize limit = context().properties().limits.maxStorageBufferRange;
    // A storage buffer one word past the limit (128 MiB on lavapipe) is refused with a reason, before any
    // allocation.
    try {
        GpuBuffer too_large(context(), static_cast<size_t>(limit) + 4);
        ADD_FAILURE() << "a " << limit + 4 << "-byte storage buffer was accepted";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("maxStorageBufferRange"), std::string::npos) << error.what();
    }
    EXPECT_THROW(GpuBuffer(context(), size_t{1} << 40), std::runtime_error);
}

TEST_F(VulkanTest, BufferRoundsSizesAndMovesOwnership) {
    EXPECT_EQ(GpuBuffer(context(), 0).size(), 4u);
    EXPECT_EQ(GpuBuffer(context(), 5).size(), 8u);
    EXPECT_EQ(GpuBuffer(context(), 8).size(), 8u);

    GpuBuffer original(context(), 3 * sizeof(uint32_t));
    original.uploadVector(std::vector<uint32_t>{7, 8, 9});
    const VkBuffer handle = original.handle();
    GpuBuffer moved(std::move(original));
    EXPECT_EQ(moved.handle(), handle);
    EXPECT_EQ(original.handle(), VK_NULL_HANDLE);
    EXPECT_EQ(original.size(), 0u);
    GpuBuffer assigned;
    assigned = std::move(moved);
    EXPECT_EQ(assigned.handle(), handle);
    EXPECT_EQ(assigned.downloadVector<uint32_t>(3), (std::vector<uint32_t>{7, 8, 9}));

    // Reads and writes outside the buffer are refused, not performed.
    const uint32_t word = 1;
    EXPECT_THROW(assigned.upload(&word, sizeof(word), 12), std::out_of_range);
    EXPECT_THROW(assigned.downloadVector<uint32_t>(4), std::out_of_range);
}

TEST_F(VulkanTest, PipelineRefusesBadArguments) {
    EXPECT_THROW(ComputePipeline(context(), kSmokeScaleAddCompSpirv, sizeof(kSmokeScaleAddCompSpirv), 3, 132),
                 std::invalid_argument);
    EXPECT_THROW(ComputePipeline(context(), kSmokeScaleAddCompSpirv, 6, 3, 12), std::invalid_argument);
    ComputePipeline pipeline(context(), kSmokeScaleAddCompSpirv, sizeof(kSmokeScaleAddCompSpirv), 3, sizeof(ScaleAddParams));
    GpuBuffer buffer(context(), 16);
    EXPECT_THROW(pipeline.bindBuffers({&buffer, &buffer}), std::invalid_argument);
    EXPECT_THROW(pipeline.bindBuffers({&buffer, nullptr, &buffer}), std::invalid_argument);
}

TEST_F(VulkanTest, MissingBarrierIsReportedBySynchronizationValidation) {
    // A dispatch reading what the previous one wrote, with no barrier between them: a read-after-write hazard
    // that synchronization validation reports (lavapipe runs dispatches one after the other, so it is harmless
    // here). Note: layer 1.3.239 does not report a write-after-write between two dispatches of one pipeline.
    if (const char* sync = std::getenv("GUSUKU_SYNC_VALIDATION"); sync && std::string(sync) == "0")
        GTEST_SKIP() << "GUSUKU_SYNC_VALIDATION=0 turns synchronization validation off";
    constexpr uint32_t count = 64;
    GpuBuffer first(context(), count * sizeof(float));
    GpuBuffer second(context(), count * sizeof(float));
    GpuBuffer third(context(), count * sizeof(float));
    GpuBuffer key_sum_first(context(), sizeof(uint32_t));
    GpuBuffer key_sum_second(context(), sizeof(uint32_t));
    ComputePipeline producer(context(), kSmokeScaleAddCompSpirv, sizeof(kSmokeScaleAddCompSpirv), 3, sizeof(ScaleAddParams));
    ComputePipeline consumer(context(), kSmokeScaleAddCompSpirv, sizeof(kSmokeScaleAddCompSpirv), 3, sizeof(ScaleAddParams));
    producer.bindBuffers({&first, &second, &key_sum_first});
    consumer.bindBuffers({&second, &third, &key_sum_second});
    const ScaleAddParams params{1.0f, 0.0f, count};
    const size_t count_before = context().validationMessageCount();
    context().submitAndWait([&](VkCommandBuffer cmd) {
        producer.recordDispatch(cmd, &params, 1);
        consumer.recordDispatch(cmd, &params, 1);
        recordComputeBarrier(cmd);
    });
    EXPECT_GT(context().validationMessageCount(), count_before)
        << "synchronization validation is off or missed the hazard";
    const std::vector<std::string> messages = takeValidationMessages();
    ASSERT_FALSE(messages.empty());
    bool names_the_hazard = false;
    for (const std::string& message : messages)
        names_the_hazard |= message.find("SYNC-HAZARD-READ-AFTER-WRITE") != std::string::npos;
    EXPECT_TRUE(names_the_hazard) << messages.front();
}

TEST_F(VulkanTest, DependentDispatchesInOneSubmissionSeeEachOthersWrites) {
    // y = 2x + 1 twice in one command buffer, separated by recordComputeBarrier: 4x + 3, exact for small ints.
    // Also shows the barrier is enough for synchronization validation (the fixture fails on any message).
    constexpr uint32_t count = 1000;
    std::vector<float> inputs(count);
    for (uint32_t index = 0; index < count; ++index) inputs[index] = static_cast<float>(index);
    GpuBuffer first(context(), count * sizeof(float));
    GpuBuffer second(context(), count * sizeof(float));
    GpuBuffer key_sum_first(context(), sizeof(uint32_t));
    GpuBuffer key_sum_second(context(), sizeof(uint32_t));
    first.uploadVector(inputs);
    const ScaleAddParams params{2.0f, 1.0f, count};
    // One pipeline per binding: a pipeline owns one descriptor set (see gpu_compute.h).
    ComputePipeline forward(context(), kSmokeScaleAddCompSpirv, sizeof(kSmokeScaleAddCompSpirv), 3, sizeof(ScaleAddParams));
    ComputePipeline back(context(), kSmokeScaleAddCompSpirv, sizeof(kSmokeScaleAddCompSpirv), 3, sizeof(ScaleAddParams));
    forward.bindBuffers({&first, &second, &key_sum_first});
    back.bindBuffers({&second, &first, &key_sum_second});
    const uint32_t groups = (count + kWorkgroupSize - 1) / kWorkgroupSize;
    context().submitAndWait([&](VkCommandBuffer cmd) {
        forward.recordDispatch(cmd, &params, groups);
        recordComputeBarrier(cmd);
        back.recordDispatch(cmd, &params, groups);
        recordComputeBarrier(cmd);
    });
    const std::vector<float> outputs = first.downloadVector<float>(count);
    for (uint32_t index = 0; index < count; ++index) ASSERT_EQ(outputs[index], 4.0f * index + 3.0f) << index;
}

}  // namespace
}  // namespace gusuku
