#include "renderer.hpp"

#include "scene_frag.h"  // the renderer's shaders as SPIR-V (glslangValidator --vn)
#include "scene_vert.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <array>
#include <cstring>

namespace dropin {

namespace {

// Two triangles a b c, a c d with the face's normal.
void add_quad(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 albedo) {
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    for (glm::vec3 p : {a, b, c, a, c, d}) s.vertices.push_back({p, n, albedo});
}

struct Push {
    glm::mat4 view_projection;
    glm::vec4 light_position;
    glm::vec4 light_color;
};

VkShaderModule module(const Gpu& gpu, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = bytes;
    info.pCode = code;
    VkShaderModule m = VK_NULL_HANDLE;
    DROPIN_CHECK(vkCreateShaderModule(gpu.device, &info, nullptr, &m));
    return m;
}

}  // namespace

Scene make_scene() {
    Scene s;
    add_quad(s, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, glm::vec3(0.7f));             // floor, facing up
    add_quad(s, {-1, 0, -1}, {1, 0, -1}, {1, 1.5f, -1}, {-1, 1.5f, -1}, {0.8f, 0.3f, 0.2f});  // back wall
    const glm::vec3 lo{-0.55f, 0.0f, -0.35f}, hi{-0.05f, 0.5f, 0.15f}, box{0.3f, 0.5f, 0.8f};
    add_quad(s, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}, box);  // top
    add_quad(s, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}, box);  // front
    add_quad(s, {hi.x, lo.y, lo.z}, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, box);  // back
    add_quad(s, {lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z}, box);  // left
    add_quad(s, {hi.x, lo.y, hi.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, box);  // right
    s.light_position = {0.5f, 1.2f, 0.4f};
    s.light_color = {1.2f, 1.1f, 0.9f};
    return s;
}

Camera make_camera(uint32_t width, uint32_t height) {
    Camera c;
    c.eye = {0.3f, 1.5f, 2.3f};
    c.projection = glm::perspectiveRH_ZO(glm::radians(50.0f), float(width) / float(height), 0.1f, 10.0f);
    c.projection[1][1] = -c.projection[1][1];  // Vulkan's clip y points down the image
    c.view = glm::lookAtRH(c.eye, glm::vec3(0.0f, 0.35f, -0.2f), glm::vec3(0, 1, 0));
    c.view_projection = c.projection * c.view;
    return c;
}

Rasterizer Rasterizer::create(const Gpu& gpu, const Scene& scene, uint32_t width, uint32_t height) {
    Rasterizer r;
    const VkImageUsageFlags attachment = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    const VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT;
    r.colour = GpuImage::create(gpu, width, height, VK_FORMAT_R16G16B16A16_SFLOAT,
                                attachment | VK_IMAGE_USAGE_STORAGE_BIT);  // post passes read it as storage
    r.normal = GpuImage::create(gpu, width, height, VK_FORMAT_R16G16_SFLOAT, attachment | sampled);
    r.albedo = GpuImage::create(gpu, width, height, VK_FORMAT_R8G8B8A8_UNORM, attachment | sampled);
    r.depth = GpuImage::create(gpu, width, height, VK_FORMAT_D32_SFLOAT,
                               VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | sampled, VK_IMAGE_ASPECT_DEPTH_BIT);
    r.output = GpuImage::create(gpu, width, height, VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT);
    r.vertex_count = uint32_t(scene.vertices.size());
    r.vertex_buffer =
        HostBuffer::create(gpu, scene.vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    std::memcpy(r.vertex_buffer.mapped, scene.vertices.data(), r.vertex_buffer.size);

    VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(Push)};
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &push;
    DROPIN_CHECK(vkCreatePipelineLayout(gpu.device, &layout_info, nullptr, &r.layout));

    const VkShaderModule vert = module(gpu, scene_vert, sizeof(scene_vert));
    const VkShaderModule frag = module(gpu, scene_frag, sizeof(scene_frag));
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag;
    stages[1].pName = "main";
    const VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription attributes[3] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
        {2, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, albedo)}};
    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertex_input.vertexBindingDescriptionCount = 1;
    vertex_input.pVertexBindingDescriptions = &binding;
    vertex_input.vertexAttributeDescriptionCount = 3;
    vertex_input.pVertexAttributeDescriptions = attributes;
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    const VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {width, height}};
    VkPipelineViewportStateCreateInfo viewport_state{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport_state.viewportCount = viewport_state.scissorCount = 1;
    viewport_state.pViewports = &viewport;
    viewport_state.pScissors = &scissor;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS;
    std::array<VkPipelineColorBlendAttachmentState, 3> blend{};
    for (auto& b : blend) b.colorWriteMask = 0xf;
    VkPipelineColorBlendStateCreateInfo blend_state{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend_state.attachmentCount = uint32_t(blend.size());
    blend_state.pAttachments = blend.data();
    const VkFormat formats[3] = {r.colour.format, r.normal.format, r.albedo.format};
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = 3;
    rendering.pColorAttachmentFormats = formats;
    rendering.depthAttachmentFormat = r.depth.format;
    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport_state;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend_state;
    info.layout = r.layout;
    DROPIN_CHECK(vkCreateGraphicsPipelines(gpu.device, VK_NULL_HANDLE, 1, &info, nullptr, &r.pipeline));
    vkDestroyShaderModule(gpu.device, vert, nullptr);
    vkDestroyShaderModule(gpu.device, frag, nullptr);
    return r;
}

void Rasterizer::draw(VkCommandBuffer cmd, const Scene& scene, const Camera& camera) const {
    const VkImageLayout attachment_layout = VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL;
    for (const GpuImage* i : {&colour, &normal, &albedo, &depth}) {
        transition(cmd, *i, VK_IMAGE_LAYOUT_UNDEFINED, attachment_layout);
    }
    std::array<VkRenderingAttachmentInfo, 3> targets{};
    const GpuImage* colours[3] = {&colour, &normal, &albedo};
    for (int i = 0; i < 3; ++i) {
        targets[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        targets[i].imageView = colours[i]->view;
        targets[i].imageLayout = attachment_layout;
        targets[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        targets[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    }
    VkRenderingAttachmentInfo depth_target{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth_target.imageView = depth.view;
    depth_target.imageLayout = attachment_layout;
    depth_target.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth_target.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth_target.clearValue.depthStencil = {1.0f, 0};  // far
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {colour.width, colour.height}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 3;
    rendering.pColorAttachments = targets.data();
    rendering.pDepthAttachment = &depth_target;
    vkCmdBeginRendering(cmd, &rendering);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    const Push push{camera.view_projection, glm::vec4(scene.light_position, 1.0f), glm::vec4(scene.light_color, 0.0f)};
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(Push), &push);
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer.buffer, &offset);
    vkCmdDraw(cmd, vertex_count, 1, 0, 0);
    vkCmdEndRendering(cmd);
    transition(cmd, colour, attachment_layout, VK_IMAGE_LAYOUT_GENERAL);
    transition(cmd, output, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    for (const GpuImage* i : {&normal, &albedo, &depth}) {
        transition(cmd, *i, attachment_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }
}

void Rasterizer::destroy(const Gpu& gpu) {
    vkDestroyPipeline(gpu.device, pipeline, nullptr);
    vkDestroyPipelineLayout(gpu.device, layout, nullptr);
    vertex_buffer.destroy(gpu);
    for (GpuImage* i : {&colour, &normal, &albedo, &depth, &output}) i->destroy(gpu);
}

}  // namespace dropin
