// Render passes and graphics pipelines of the runtime (see runtime_pipelines.h).

#include "runtime_pipelines.h"

#include <stdexcept>

namespace gusuku::runtime_detail {

namespace {

// The main pass's attachment descriptions for a variant: [0] the colour it draws into, [1] depth and, with
// multisampling, [2] the composite the colour resolves into. Returns how many.
uint32_t describeMainAttachments(MainPassVariant variant, VkSampleCountFlagBits samples, VkFormat depth_stencil_format,
                                 VkAttachmentDescription (&attachments)[3]) {
    // The later variants continue a frame the earlier ones began (profiling): they load what it drew.
    const bool loads_depth = variant == MainPassVariant::kMiddle || variant == MainPassVariant::kLast;
    const bool loads_colour = loads_depth;
    const bool ends_frame = variant == MainPassVariant::kWhole || variant == MainPassVariant::kLast;
    const bool multisampled = samples != VK_SAMPLE_COUNT_1_BIT;
    for (VkAttachmentDescription& attachment : attachments) {
        attachment = {};
        attachment.samples = samples;
        attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    }
    attachments[0].format = kColourFormat;
    // A new frame's colour is not loaded: the camera-in draw writes every pixel (every sample) first
    // (camera_input.h). Single-sampled it is the composite, kept; multisampled it is kept only for the next
    // profiling variant, the frame's end keeping the resolved composite instead.
    attachments[0].loadOp = loads_colour ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachments[0].storeOp =
        multisampled && ends_frame ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
    attachments[0].initialLayout =
        loads_colour ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED;
    attachments[0].finalLayout = ends_frame && !multisampled ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL
                                                             : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    attachments[1].format = depth_stencil_format;
    attachments[1].loadOp = loads_depth ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachments[1].storeOp = ends_frame ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
    attachments[1].stencilLoadOp = attachments[1].loadOp;  // the building's marks (StencilUse), like depth
    attachments[1].stencilStoreOp = attachments[1].storeOp;
    attachments[1].initialLayout =
        loads_depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED;
    attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    if (!multisampled) return 2;
    // The composite: written whole by the resolve at the frame's end (not loaded); in the profiling variants
    // before it, no subpass uses it, so it is left alone in the layout compositeImage() promises.
    attachments[2].format = kColourFormat;
    attachments[2].samples = VK_SAMPLE_COUNT_1_BIT;
    attachments[2].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachments[2].storeOp = ends_frame ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachments[2].initialLayout =
        ends_frame ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    attachments[2].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    return 3;
}

}  // namespace

VkFormat mainDepthStencilFormat(VkPhysicalDevice physical_device) {
    for (VkFormat format : {VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_D24_UNORM_S8_UINT}) {
        VkFormatProperties properties{};
        vkGetPhysicalDeviceFormatProperties(physical_device, format, &properties);
        if (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) return format;
    }
    return VK_FORMAT_UNDEFINED;
}

VkRenderPass createMainRenderPass(VkDevice device, MainPassVariant variant, VkSampleCountFlagBits samples,
                                  VkFormat depth_stencil_format) {
    VkAttachmentDescription attachments[3];
    const uint32_t attachment_count = describeMainAttachments(variant, samples, depth_stencil_format, attachments);
    const bool ends_frame = variant == MainPassVariant::kWhole || variant == MainPassVariant::kLast;

    VkAttachmentReference colour_reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference depth_reference{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &colour_reference;
    subpass.pDepthStencilAttachment = &depth_reference;
    // Multisampled, the frame's end resolves the colour into the composite. The profiling variants before it
    // name no resolve: one subpass each, so they stay compatible with the others (Vulkan's render pass
    // compatibility ignores resolve attachments when the passes have a single subpass) and share pipelines.
    VkAttachmentReference resolve_reference{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    if (attachment_count == 3 && ends_frame) subpass.pResolveAttachments = &resolve_reference;

    // In: the last pass's colour and depth writes, the earlier reads of this slot's composite (the app's copies
    // and samplers, the read-back: write after read), and the shadow maps, uniforms and colour state written
    // before (their own barriers make them visible to fragment shaders). Out: the copy to the host.
    VkSubpassDependency dependencies[2]{};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                   VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                   VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    dependencies[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                   VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                   VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask =
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[1].srcAccessMask =
        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                   VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
                                    VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;

    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = attachment_count;
    info.pAttachments = attachments;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = dependencies;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    checkVk(vkCreateRenderPass(device, &info, nullptr, &render_pass), "vkCreateRenderPass (main)");
    return render_pass;
}

VkRenderPass createShadowRenderPass(VkDevice device) {
    VkAttachmentDescription depth{};
    depth.format = kDepthFormat;
    depth.samples = VK_SAMPLE_COUNT_1_BIT;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    depth.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    depth.finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkAttachmentReference depth_reference{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.pDepthStencilAttachment = &depth_reference;
    // In: the previous frame's fragment shaders read this map (write after read). Out: this frame's read it.
    VkSubpassDependency dependencies[2]{};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    dependencies[0].srcAccessMask = 0;
    dependencies[0].dstStageMask =
        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[0].dstAccessMask =
        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &depth;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = dependencies;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    checkVk(vkCreateRenderPass(device, &info, nullptr, &render_pass), "vkCreateRenderPass (shadow)");
    return render_pass;
}

namespace {

// The colour attachment's blend state for a pipeline's BlendMode.
VkPipelineColorBlendAttachmentState blendAttachmentFor(const GraphicsPipelineDescription& description) {
    VkPipelineColorBlendAttachmentState blend_attachment{};
    switch (description.blend) {
        case BlendMode::kOpaque:
            // With alpha to coverage the output alpha is a coverage, not the composite's: leave the
            // attachment's alpha as the camera draw wrote it.
            blend_attachment.colorWriteMask =
                VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT;
            if (!description.alpha_to_coverage) blend_attachment.colorWriteMask |= VK_COLOR_COMPONENT_A_BIT;
            break;
        case BlendMode::kMultiplyTwice:
            blend_attachment.blendEnable = VK_TRUE;
            blend_attachment.srcColorBlendFactor = VK_BLEND_FACTOR_DST_COLOR;
            blend_attachment.dstColorBlendFactor = VK_BLEND_FACTOR_SRC_COLOR;
            blend_attachment.colorBlendOp = VK_BLEND_OP_ADD;
            blend_attachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
            blend_attachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
            blend_attachment.alphaBlendOp = VK_BLEND_OP_ADD;
            blend_attachment.colorWriteMask =
                VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT;
            break;
        case BlendMode::kNoColourWrites: blend_attachment.colorWriteMask = 0; break;
    }
    return blend_attachment;
}

}  // namespace

VkPipeline createGraphicsPipeline(VkDevice device, const GraphicsPipelineDescription& description) {
    VkShaderModule modules[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
    auto makeModule = [&](const uint32_t* code, size_t bytes) {
        VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        info.codeSize = bytes;
        info.pCode = code;
        VkShaderModule module = VK_NULL_HANDLE;
        checkVk(vkCreateShaderModule(device, &info, nullptr, &module), "vkCreateShaderModule");
        return module;
    };
    VkPipeline pipeline = VK_NULL_HANDLE;
    try {
        VkPipelineShaderStageCreateInfo stages[2]{};
        uint32_t stage_count = 1;
        modules[0] = makeModule(description.vertex_spirv, description.vertex_spirv_bytes);
        stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = modules[0];
        stages[0].pName = "main";
        if (description.fragment_spirv != nullptr) {
            modules[1] = makeModule(description.fragment_spirv, description.fragment_spirv_bytes);
            stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
            stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
            stages[1].module = modules[1];
            stages[1].pName = "main";
            stages[1].pSpecializationInfo = description.fragment_specialization;
            stage_count = 2;
        }

        VkVertexInputBindingDescription binding{0, description.vertex_input.stride, VK_VERTEX_INPUT_RATE_VERTEX};
        VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
        if (description.vertex_input.stride > 0) {
            vertex_input.vertexBindingDescriptionCount = 1;
            vertex_input.pVertexBindingDescriptions = &binding;
            vertex_input.vertexAttributeDescriptionCount = uint32_t(description.vertex_input.attributes.size());
            vertex_input.pVertexAttributeDescriptions = description.vertex_input.attributes.data();
        }
        VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
        assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
        viewport.viewportCount = 1;
        viewport.scissorCount = 1;
        VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = VK_CULL_MODE_NONE;
        raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        raster.lineWidth = 1.0f;
        VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
        multisample.rasterizationSamples = description.samples;
        multisample.alphaToCoverageEnable = description.alpha_to_coverage ? VK_TRUE : VK_FALSE;
        VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
        depth.depthTestEnable = description.depth_test ? VK_TRUE : VK_FALSE;
        depth.depthWriteEnable = description.depth_write ? VK_TRUE : VK_FALSE;
        depth.depthCompareOp = description.depth_compare;
        if (description.stencil != StencilUse::kNone) {
            const bool mark = description.stencil == StencilUse::kMarkBuilding;
            VkStencilOpState stencil{};
            stencil.failOp = VK_STENCIL_OP_KEEP;
            stencil.depthFailOp = VK_STENCIL_OP_KEEP;
            stencil.passOp = mark ? VK_STENCIL_OP_REPLACE : VK_STENCIL_OP_KEEP;
            stencil.compareOp = mark ? VK_COMPARE_OP_ALWAYS : VK_COMPARE_OP_EQUAL;
            stencil.compareMask = 1;
            stencil.writeMask = mark ? 1u : 0u;
            stencil.reference = mark ? 1u : 0u;
            depth.stencilTestEnable = VK_TRUE;
            depth.front = depth.back = stencil;
        }
        const VkPipelineColorBlendAttachmentState blend_attachment = blendAttachmentFor(description);
        VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
        blend.attachmentCount = description.has_colour_attachment ? 1 : 0;
        blend.pAttachments = &blend_attachment;
        const VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
        dynamic.dynamicStateCount = 2;
        dynamic.pDynamicStates = dynamic_states;

        VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
        info.stageCount = stage_count;
        info.pStages = stages;
        info.pVertexInputState = &vertex_input;
        info.pInputAssemblyState = &assembly;
        info.pViewportState = &viewport;
        info.pRasterizationState = &raster;
        info.pMultisampleState = &multisample;
        info.pDepthStencilState = &depth;
        info.pColorBlendState = &blend;
        info.pDynamicState = &dynamic;
        info.layout = description.layout;
        info.renderPass = description.render_pass;
        checkVk(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
                "vkCreateGraphicsPipelines");
    } catch (...) {
        for (VkShaderModule module : modules)
            if (module != VK_NULL_HANDLE) vkDestroyShaderModule(device, module, nullptr);
        throw;
    }
    for (VkShaderModule module : modules)
        if (module != VK_NULL_HANDLE) vkDestroyShaderModule(device, module, nullptr);
    return pipeline;
}

VkFramebuffer createFramebuffer(VkDevice device, VkRenderPass render_pass, const std::vector<VkImageView>& views,
                                uint32_t width, uint32_t height) {
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = render_pass;
    info.attachmentCount = uint32_t(views.size());
    info.pAttachments = views.data();
    info.width = width;
    info.height = height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    checkVk(vkCreateFramebuffer(device, &info, nullptr, &framebuffer), "vkCreateFramebuffer");
    return framebuffer;
}

void recordViewport(VkCommandBuffer cmd, uint32_t width, uint32_t height) {
    const VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {width, height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace gusuku::runtime_detail
