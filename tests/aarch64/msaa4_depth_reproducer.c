/* A gusuku-free reproducer of the AArch64 msaa 4 crash (docs/platforms.md, "AArch64"): plain Vulkan 1.0, one
 * triangle drawn into a 4-sample VK_FORMAT_D32_SFLOAT depth buffer, nothing else. On x86_64 lavapipe, and on
 * arm64 lavapipe on ARM hardware, it prints one line and exits 0. Under qemu-user (Debian 12's qemu 7.2,
 * qemu-aarch64 on x86_64) running Debian 12's arm64 lavapipe (Mesa 22.3.6, LLVM 15) the draw dies with SIGSEGV
 * in the code lavapipe's LLVM JIT compiled, as the runtime's first msaa 4 frame does: the emulated driver's
 * fault, not gusuku's. scripts/cross-build-aarch64.sh runs it first and runs the runtime's tests at msaa 4 only
 * when it passes (at msaa 1 while it crashes). With the argument 1 it draws the same at one sample, which runs
 * there: the control that tells a broken emulator or driver install from the msaa 4 crash.
 *   qemu-aarch64 -L / ./msaa4_depth_reproducer [1|4]    (VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.aarch64.json)
 */
#include <stdio.h>
#include <stdlib.h>

#include <vulkan/vulkan.h>

#define CHECK(call)                                                                   \
    do {                                                                              \
        VkResult result_ = (call);                                                    \
        if (result_ != VK_SUCCESS) {                                                  \
            fprintf(stderr, "msaa4_depth_reproducer: %s: VkResult %d\n", #call, result_); \
            exit(2);                                                                  \
        }                                                                             \
    } while (0)

enum { kSize = 64 };

/* void main() { gl_Position = vec4(float(gl_VertexIndex == 1) * 4.0 - 1.0, float(gl_VertexIndex == 2) * 4.0 - 1.0,
 * 0.5, 1.0); } as SPIR-V (glslangValidator -V -g0): a triangle that covers the whole framebuffer. */
static const uint32_t kVertexShader[] = {
    0x07230203,0x00010000,0x0008000b,0x0000002d,0x00000000,0x00020011,0x00000001,0x0006000b,
    0x00000001,0x4c534c47,0x6474732e,0x3035342e,0x00000000,0x0003000e,0x00000000,0x00000001,
    0x0007000f,0x00000000,0x00000004,0x6e69616d,0x00000000,0x0000000c,0x00000024,0x00040047,
    0x0000000c,0x0000000b,0x0000002a,0x00050048,0x00000022,0x00000000,0x0000000b,0x00000000,
    0x00050048,0x00000022,0x00000001,0x0000000b,0x00000001,0x00050048,0x00000022,0x00000002,
    0x0000000b,0x00000003,0x00050048,0x00000022,0x00000003,0x0000000b,0x00000004,0x00030047,
    0x00000022,0x00000002,0x00020013,0x00000002,0x00030021,0x00000003,0x00000002,0x00030016,
    0x00000006,0x00000020,0x00040017,0x00000007,0x00000006,0x00000002,0x00040020,0x00000008,
    0x00000007,0x00000007,0x00040015,0x0000000a,0x00000020,0x00000001,0x00040020,0x0000000b,
    0x00000001,0x0000000a,0x0004003b,0x0000000b,0x0000000c,0x00000001,0x0004002b,0x0000000a,
    0x0000000e,0x00000001,0x00020014,0x0000000f,0x0004002b,0x00000006,0x00000011,0x00000000,
    0x0004002b,0x00000006,0x00000012,0x3f800000,0x0004002b,0x00000006,0x00000014,0x40800000,
    0x0004002b,0x0000000a,0x00000018,0x00000002,0x00040017,0x0000001e,0x00000006,0x00000004,
    0x00040015,0x0000001f,0x00000020,0x00000000,0x0004002b,0x0000001f,0x00000020,0x00000001,
    0x0004001c,0x00000021,0x00000006,0x00000020,0x0006001e,0x00000022,0x0000001e,0x00000006,
    0x00000021,0x00000021,0x00040020,0x00000023,0x00000003,0x00000022,0x0004003b,0x00000023,
    0x00000024,0x00000003,0x0004002b,0x0000000a,0x00000025,0x00000000,0x0004002b,0x00000006,
    0x00000027,0x3f000000,0x00040020,0x0000002b,0x00000003,0x0000001e,0x00050036,0x00000002,
    0x00000004,0x00000000,0x00000003,0x000200f8,0x00000005,0x0004003b,0x00000008,0x00000009,
    0x00000007,0x0004003d,0x0000000a,0x0000000d,0x0000000c,0x000500aa,0x0000000f,0x00000010,
    0x0000000d,0x0000000e,0x000600a9,0x00000006,0x00000013,0x00000010,0x00000012,0x00000011,
    0x00050085,0x00000006,0x00000015,0x00000013,0x00000014,0x00050083,0x00000006,0x00000016,
    0x00000015,0x00000012,0x0004003d,0x0000000a,0x00000017,0x0000000c,0x000500aa,0x0000000f,
    0x00000019,0x00000017,0x00000018,0x000600a9,0x00000006,0x0000001a,0x00000019,0x00000012,
    0x00000011,0x00050085,0x00000006,0x0000001b,0x0000001a,0x00000014,0x00050083,0x00000006,
    0x0000001c,0x0000001b,0x00000012,0x00050050,0x00000007,0x0000001d,0x00000016,0x0000001c,
    0x0003003e,0x00000009,0x0000001d,0x0004003d,0x00000007,0x00000026,0x00000009,0x00050051,
    0x00000006,0x00000028,0x00000026,0x00000000,0x00050051,0x00000006,0x00000029,0x00000026,
    0x00000001,0x00070050,0x0000001e,0x0000002a,0x00000028,0x00000029,0x00000027,0x00000012,
    0x00050041,0x0000002b,0x0000002c,0x00000024,0x00000025,0x0003003e,0x0000002c,0x0000002a,
    0x000100fd,0x00010038
};

int main(int argc, char** argv) {
    const int sample_count = argc > 1 ? atoi(argv[1]) : 4;
    if (sample_count != 1 && sample_count != 4) {
        fprintf(stderr, "msaa4_depth_reproducer: samples: %s is not 1 or 4\n", argv[1]);
        return 2;
    }
    const VkSampleCountFlagBits samples = sample_count == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
    VkApplicationInfo application = {VK_STRUCTURE_TYPE_APPLICATION_INFO};
    application.apiVersion = VK_API_VERSION_1_0;
    VkInstanceCreateInfo instance_info = {VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pApplicationInfo = &application;
    VkInstance instance;
    CHECK(vkCreateInstance(&instance_info, NULL, &instance));
    uint32_t count = 1;
    VkPhysicalDevice physical;
    VkResult enumerated = vkEnumeratePhysicalDevices(instance, &count, &physical);
    if ((enumerated != VK_SUCCESS && enumerated != VK_INCOMPLETE) || count == 0) {
        fprintf(stderr, "msaa4_depth_reproducer: no Vulkan device\n");
        return 2;
    }
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(physical, &properties);
    if (!(properties.limits.framebufferDepthSampleCounts & samples)) {
        fprintf(stderr, "msaa4_depth_reproducer: %s has no %d-sample depth\n", properties.deviceName, sample_count);
        return 2;
    }
    uint32_t family_count = 8, family = 0;
    VkQueueFamilyProperties families[8];
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &family_count, families);
    while (family < family_count && !(families[family].queueFlags & VK_QUEUE_GRAPHICS_BIT)) ++family;
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info = {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo device_info = {VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    VkDevice device;
    CHECK(vkCreateDevice(physical, &device_info, NULL, &device));
    VkQueue queue;
    vkGetDeviceQueue(device, family, 0, &queue);

    /* The depth buffer: D32_SFLOAT, 4 samples (or 1), in device memory. */
    VkImageCreateInfo image_info = {VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    image_info.imageType = VK_IMAGE_TYPE_2D;
    image_info.format = VK_FORMAT_D32_SFLOAT;
    image_info.extent = (VkExtent3D){kSize, kSize, 1};
    image_info.mipLevels = image_info.arrayLayers = 1;
    image_info.samples = samples;
    image_info.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    VkImage image;
    CHECK(vkCreateImage(device, &image_info, NULL, &image));
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device, image, &requirements);
    VkMemoryAllocateInfo allocate = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocate.allocationSize = requirements.size;
    while (!(requirements.memoryTypeBits & (1u << allocate.memoryTypeIndex))) ++allocate.memoryTypeIndex;
    VkDeviceMemory memory;
    CHECK(vkAllocateMemory(device, &allocate, NULL, &memory));
    CHECK(vkBindImageMemory(device, image, memory, 0));
    VkImageViewCreateInfo view_info = {VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view_info.image = image;
    view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = VK_FORMAT_D32_SFLOAT;
    view_info.subresourceRange = (VkImageSubresourceRange){VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
    VkImageView view;
    CHECK(vkCreateImageView(device, &view_info, NULL, &view));

    /* A depth-only render pass and framebuffer. */
    VkAttachmentDescription attachment = {0};
    attachment.format = VK_FORMAT_D32_SFLOAT;
    attachment.samples = samples;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    VkAttachmentReference depth_reference = {0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass = {0};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.pDepthStencilAttachment = &depth_reference;
    VkRenderPassCreateInfo pass_info = {VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    pass_info.attachmentCount = 1;
    pass_info.pAttachments = &attachment;
    pass_info.subpassCount = 1;
    pass_info.pSubpasses = &subpass;
    VkRenderPass pass;
    CHECK(vkCreateRenderPass(device, &pass_info, NULL, &pass));
    VkFramebufferCreateInfo framebuffer_info = {VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    framebuffer_info.renderPass = pass;
    framebuffer_info.attachmentCount = 1;
    framebuffer_info.pAttachments = &view;
    framebuffer_info.width = framebuffer_info.height = kSize;
    framebuffer_info.layers = 1;
    VkFramebuffer framebuffer;
    CHECK(vkCreateFramebuffer(device, &framebuffer_info, NULL, &framebuffer));

    /* The pipeline: the vertex shader alone, the same samples, depth test and write. */
    VkShaderModuleCreateInfo module_info = {VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = sizeof kVertexShader;
    module_info.pCode = kVertexShader;
    VkShaderModule module;
    CHECK(vkCreateShaderModule(device, &module_info, NULL, &module));
    VkPipelineShaderStageCreateInfo stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stage.stage = VK_SHADER_STAGE_VERTEX_BIT;
    stage.module = module;
    stage.pName = "main";
    VkPipelineVertexInputStateCreateInfo vertex_input = {VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo assembly = {VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkViewport viewport = {0, 0, kSize, kSize, 0, 1};
    VkRect2D scissor = {{0, 0}, {kSize, kSize}};
    VkPipelineViewportStateCreateInfo viewport_state = {VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport_state.viewportCount = viewport_state.scissorCount = 1;
    viewport_state.pViewports = &viewport;
    viewport_state.pScissors = &scissor;
    VkPipelineRasterizationStateCreateInfo raster = {VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample = {VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = samples;
    VkPipelineDepthStencilStateCreateInfo depth = {VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS;
    VkPipelineLayoutCreateInfo layout_info = {VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    VkPipelineLayout layout;
    CHECK(vkCreatePipelineLayout(device, &layout_info, NULL, &layout));
    VkGraphicsPipelineCreateInfo pipeline_info = {VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    pipeline_info.stageCount = 1;
    pipeline_info.pStages = &stage;
    pipeline_info.pVertexInputState = &vertex_input;
    pipeline_info.pInputAssemblyState = &assembly;
    pipeline_info.pViewportState = &viewport_state;
    pipeline_info.pRasterizationState = &raster;
    pipeline_info.pMultisampleState = &multisample;
    pipeline_info.pDepthStencilState = &depth;
    pipeline_info.layout = layout;
    pipeline_info.renderPass = pass;
    VkPipeline pipeline;
    CHECK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, NULL, &pipeline));

    /* One draw, submitted and waited for. */
    VkCommandPoolCreateInfo pool_info = {VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.queueFamilyIndex = family;
    VkCommandPool pool;
    CHECK(vkCreateCommandPool(device, &pool_info, NULL, &pool));
    VkCommandBufferAllocateInfo command_info = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    command_info.commandPool = pool;
    command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    command_info.commandBufferCount = 1;
    VkCommandBuffer commands;
    CHECK(vkAllocateCommandBuffers(device, &command_info, &commands));
    VkCommandBufferBeginInfo begin = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    CHECK(vkBeginCommandBuffer(commands, &begin));
    VkClearValue clear = {0};
    clear.depthStencil.depth = 1.0f;
    VkRenderPassBeginInfo pass_begin = {VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    pass_begin.renderPass = pass;
    pass_begin.framebuffer = framebuffer;
    pass_begin.renderArea = scissor;
    pass_begin.clearValueCount = 1;
    pass_begin.pClearValues = &clear;
    vkCmdBeginRenderPass(commands, &pass_begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdDraw(commands, 3, 1, 0, 0);
    vkCmdEndRenderPass(commands);
    CHECK(vkEndCommandBuffer(commands));
    VkSubmitInfo submit = {VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    CHECK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE));
    CHECK(vkQueueWaitIdle(queue));
    printf("msaa4_depth_reproducer: %s drew one triangle into a %d-sample D32 depth buffer\n", properties.deviceName,
           sample_count);

    vkDestroyCommandPool(device, pool, NULL);
    vkDestroyPipeline(device, pipeline, NULL);
    vkDestroyPipelineLayout(device, layout, NULL);
    vkDestroyShaderModule(device, module, NULL);
    vkDestroyFramebuffer(device, framebuffer, NULL);
    vkDestroyRenderPass(device, pass, NULL);
    vkDestroyImageView(device, view, NULL);
    vkDestroyImage(device, image, NULL);
    vkFreeMemory(device, memory, NULL);
    vkDestroyDevice(device, NULL);
    vkDestroyInstance(instance, NULL);
    return 0;
}
