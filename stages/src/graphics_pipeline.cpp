#include "vplkit/graphics_pipeline.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace vplkit {

namespace {

// One set-0 layout for all stages: a binding used by several stages gets all their stage bits.
std::vector<VkDescriptorSetLayoutBinding> merge_bindings(std::span<const ShaderStageDesc> stages) {
    std::map<uint32_t, VkDescriptorSetLayoutBinding> merged;
    for (const ShaderStageDesc& s : stages) {
        for (uint32_t i = 0; i < s.binding_count; ++i) {
            VkDescriptorSetLayoutBinding b = s.bindings[i];
            auto [it, inserted] = merged.emplace(b.binding, b);
            if (!inserted) {
                if (it->second.descriptorType != b.descriptorType || it->second.descriptorCount != b.descriptorCount) {
                    throw Error("graphics pipeline: binding " + std::to_string(b.binding) +
                                " has a different type or count in two shader stages");
                }
                it->second.stageFlags |= b.stageFlags;
            }
        }
    }
    std::vector<VkDescriptorSetLayoutBinding> out;
    for (const auto& [binding, b] : merged) out.push_back(b);
    return out;
}

}  // namespace

GraphicsPipeline GraphicsPipeline::create(VkDevice device, VkPipelineCache cache,
                                          std::span<const ShaderStageDesc> stages, const RasterState& state) {
    GraphicsPipeline p;
    p.device_ = device;
    p.push_descriptor_set_ =
        reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(p.device_, "vkCmdPushDescriptorSetKHR"));
    if (!p.push_descriptor_set_) throw Error("graphics pipeline: vkCmdPushDescriptorSetKHR is not available");

    const auto bindings = merge_bindings(stages);
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    set_info.bindingCount = uint32_t(bindings.size());
    set_info.pBindings = bindings.data();
    VPLKIT_CHECK(vkCreateDescriptorSetLayout(p.device_, &set_info, nullptr, &p.set_layout_));

    // One range for every stage that has push constants: they must share one block.
    for (const ShaderStageDesc& s : stages) {
        if (!s.has_push_constants) continue;
        if (p.push_range_.stageFlags != 0 && (p.push_range_.offset != s.push_constant_range.offset ||
                                              p.push_range_.size != s.push_constant_range.size)) {
            throw Error("graphics pipeline: the stages' push-constant blocks differ; use one block in both shaders");
        }
        p.push_range_.stageFlags |= s.stage;
        p.push_range_.offset = s.push_constant_range.offset;
        p.push_range_.size = s.push_constant_range.size;
    }
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &p.set_layout_;
    layout_info.pushConstantRangeCount = p.push_range_.stageFlags ? 1 : 0;
    layout_info.pPushConstantRanges = &p.push_range_;
    VPLKIT_CHECK(vkCreatePipelineLayout(p.device_, &layout_info, nullptr, &p.layout_));

    std::vector<VkShaderModule> modules;
    std::vector<VkPipelineShaderStageCreateInfo> stage_infos;
    for (const ShaderStageDesc& s : stages) {
        VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        module_info.codeSize = s.spirv_bytes;
        module_info.pCode = s.spirv;
        VkShaderModule module = VK_NULL_HANDLE;
        VkResult result = vkCreateShaderModule(p.device_, &module_info, nullptr, &module);
        if (result != VK_SUCCESS) {
            for (VkShaderModule m : modules) vkDestroyShaderModule(p.device_, m, nullptr);
            check(result, "vkCreateShaderModule");
        }
        modules.push_back(module);
        VkPipelineShaderStageCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        info.stage = s.stage;
        info.module = module;
        info.pName = s.entry_point;
        info.pSpecializationInfo = &s.specialization;
        stage_infos.push_back(info);
    }

    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertex_input.vertexBindingDescriptionCount = uint32_t(state.vertex_bindings.size());
    vertex_input.pVertexBindingDescriptions = state.vertex_bindings.data();
    vertex_input.vertexAttributeDescriptionCount = uint32_t(state.vertex_attributes.size());
    vertex_input.pVertexAttributeDescriptions = state.vertex_attributes.data();
    VkPipelineInputAssemblyStateCreateInfo input_assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    input_assembly.topology = state.topology;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = state.cull_mode;
    raster.frontFace = state.front_face;
    raster.depthBiasEnable = (state.depth_bias_constant != 0.0f || state.depth_bias_slope != 0.0f) ? VK_TRUE : VK_FALSE;
    raster.depthBiasConstantFactor = state.depth_bias_constant;
    raster.depthBiasSlopeFactor = state.depth_bias_slope;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    const bool has_depth = state.depth_format != VK_FORMAT_UNDEFINED;
    depth.depthTestEnable = has_depth && state.depth_test;
    depth.depthWriteEnable = has_depth && state.depth_write;
    depth.depthCompareOp = state.depth_compare;
    std::vector<VkPipelineColorBlendAttachmentState> blend(state.color_formats.size());
    for (auto& b : blend) {
        b.colorWriteMask =
            VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
        if (state.additive_blend) {
            b.blendEnable = VK_TRUE;
            b.srcColorBlendFactor = b.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
            b.dstColorBlendFactor = b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
            b.colorBlendOp = b.alphaBlendOp = VK_BLEND_OP_ADD;
        }
    }
    VkPipelineColorBlendStateCreateInfo color_blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    color_blend.attachmentCount = uint32_t(blend.size());
    color_blend.pAttachments = blend.data();
    const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamic_states;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = uint32_t(state.color_formats.size());
    rendering.pColorAttachmentFormats = state.color_formats.data();
    rendering.depthAttachmentFormat = state.depth_format;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = uint32_t(stage_infos.size());
    info.pStages = stage_infos.data();
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &input_assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &color_blend;
    info.pDynamicState = &dynamic;
    info.layout = p.layout_;
    VkResult result = vkCreateGraphicsPipelines(p.device_, cache, 1, &info, nullptr, &p.pipeline_);
    for (VkShaderModule m : modules) vkDestroyShaderModule(p.device_, m, nullptr);  // the pipeline keeps what it needs
    check(result, "vkCreateGraphicsPipelines");
    return p;
}

GraphicsPipeline::~GraphicsPipeline() {
    release();
}

GraphicsPipeline::GraphicsPipeline(GraphicsPipeline&& other) noexcept {
    *this = std::move(other);
}

GraphicsPipeline& GraphicsPipeline::operator=(GraphicsPipeline&& other) noexcept {
    if (this != &other) {
        release();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        set_layout_ = std::exchange(other.set_layout_, VK_NULL_HANDLE);
        layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
        pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
        push_range_ = std::exchange(other.push_range_, VkPushConstantRange{});
        push_descriptor_set_ = std::exchange(other.push_descriptor_set_, nullptr);
    }
    return *this;
}

void GraphicsPipeline::release() {
    if (device_ == VK_NULL_HANDLE) return;
    vkDestroyPipeline(device_, pipeline_, nullptr);
    vkDestroyPipelineLayout(device_, layout_, nullptr);
    vkDestroyDescriptorSetLayout(device_, set_layout_, nullptr);
    device_ = VK_NULL_HANDLE;
}

void GraphicsPipeline::bind(VkCommandBuffer cmd) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
}

void GraphicsPipeline::push_descriptor_writes(VkCommandBuffer cmd, std::span<const VkWriteDescriptorSet> writes) const {
    if (writes.empty()) return;
    push_descriptor_set_(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, uint32_t(writes.size()), writes.data());
}

void GraphicsPipeline::push_constant_bytes(VkCommandBuffer cmd, const void* data, uint32_t size) const {
    if (push_range_.stageFlags == 0)
        throw Error("graphics pipeline: push_constants() on a pipeline without push constants");
    if (size != push_range_.size) {
        throw Error("graphics pipeline: pushed " + std::to_string(size) + " bytes, the shaders' block has " +
                    std::to_string(push_range_.size));
    }
    vkCmdPushConstants(cmd, layout_, push_range_.stageFlags, push_range_.offset, size, data);
}

void begin_rendering(VkCommandBuffer cmd, const RenderTargets& targets) {
    if (targets.colors.size() != targets.clear_colors.size()) {
        throw Error("begin_rendering: one clear colour per colour target");
    }
    const ImageView* any = !targets.colors.empty() ? &targets.colors.front() : targets.depth ? &targets.depth : nullptr;
    if (!any) throw Error("begin_rendering: no render targets");
    const VkExtent2D extent = {any->width, any->height};
    std::vector<VkRenderingAttachmentInfo> colors;
    for (size_t i = 0; i < targets.colors.size(); ++i) {
        const ImageView& image = targets.colors[i];
        if (image.width != extent.width || image.height != extent.height) {
            throw Error("begin_rendering: render targets of different sizes ('" + image.name + "')");
        }
        VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = image.view;
        a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        a.clearValue.color = targets.clear_colors[i];
        colors.push_back(a);
    }
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    if (targets.depth) {
        depth.imageView = targets.depth.view;
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil = {targets.clear_depth, 0};
    }
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, extent};
    info.layerCount = 1;
    info.colorAttachmentCount = uint32_t(colors.size());
    info.pColorAttachments = colors.data();
    info.pDepthAttachment = targets.depth ? &depth : nullptr;
    vkCmdBeginRendering(cmd, &info);
    const VkViewport viewport = {0.0f, 0.0f, float(extent.width), float(extent.height), 0.0f, 1.0f};
    const VkRect2D scissor = {{0, 0}, extent};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void end_rendering(VkCommandBuffer cmd) {
    vkCmdEndRendering(cmd);
}

}  // namespace vplkit
