#pragma once
// A graphics pipeline made of a generated vertex and fragment shader (their `Module` types):
// the two set-0 layouts merged into one push-descriptor layout, one push-constant range shared by
// both stages, dynamic rendering (no render pass objects). The kit's raster stages (G-buffer,
// shadow maps) use it through RasterPipeline (created once per stages::Device, like the
// generated compute pipelines); compute stages use the generated Pipeline directly.

#include "vplkit/error.hpp"
#include "vplkit/views.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace vplkit {

// Fixed-function state of a raster pipeline.
struct RasterState {
    std::vector<VkFormat> color_formats;
    VkFormat depth_format = VK_FORMAT_UNDEFINED;
    std::vector<VkVertexInputBindingDescription> vertex_bindings;
    std::vector<VkVertexInputAttributeDescription> vertex_attributes;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkCullModeFlags cull_mode = VK_CULL_MODE_NONE;
    VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    bool depth_test = true;
    bool depth_write = true;
    VkCompareOp depth_compare = VK_COMPARE_OP_LESS;
    // Shadow maps push depth away from the surface they were rendered from.
    float depth_bias_constant = 0.0f;
    float depth_bias_slope = 0.0f;
    // Every colour target adds the fragment's value to what it holds (ONE, ONE, ADD): splatting.
    bool additive_blend = false;
};

// One shader stage as the generated Module type describes it.
struct ShaderStageDesc {
    VkShaderStageFlagBits stage;
    const char* entry_point;
    const uint32_t* spirv;
    size_t spirv_bytes;
    const VkDescriptorSetLayoutBinding* bindings;
    uint32_t binding_count;
    bool has_push_constants;
    VkPushConstantRange push_constant_range;
    VkSpecializationInfo specialization;
};

template <class M>
ShaderStageDesc stage_desc(const typename M::Spec& spec) {
    return {M::stage,
            M::entry_point,
            M::spirv,
            M::spirv_bytes,
            M::set_layout_bindings,
            M::set_layout_binding_count,
            M::has_push_constants,
            M::push_constant_range,
            spec.info()};
}

class GraphicsPipeline {
public:
    // On `device` (VK_KHR_push_descriptor enabled), through `cache` (may be VK_NULL_HANDLE).
    // Throws Error when the two stages disagree on a binding (same number, different type) or use
    // push constants of different sizes. Debug names are the caller's (handle()).
    static GraphicsPipeline create(VkDevice device, VkPipelineCache cache, std::span<const ShaderStageDesc> stages,
                                   const RasterState& state);

    // From the generated Module types of a vertex and a fragment shader. If both stages have push
    // constants they must be the same block (the same bytes are pushed to both).
    template <class VS, class FS>
    static GraphicsPipeline create(VkDevice device, VkPipelineCache cache, const RasterState& state,
                                   const typename VS::Spec& vertex_spec = {},
                                   const typename FS::Spec& fragment_spec = {}) {
        static_assert(VS::stage == VK_SHADER_STAGE_VERTEX_BIT && FS::stage == VK_SHADER_STAGE_FRAGMENT_BIT,
                      "GraphicsPipeline::create<VS, FS>: a vertex then a fragment shader Module");
        const ShaderStageDesc stages[2] = {stage_desc<VS>(vertex_spec), stage_desc<FS>(fragment_spec)};
        return create(device, cache, stages, state);
    }

    GraphicsPipeline() = default;
    ~GraphicsPipeline();
    GraphicsPipeline(GraphicsPipeline&& other) noexcept;
    GraphicsPipeline& operator=(GraphicsPipeline&& other) noexcept;
    GraphicsPipeline(const GraphicsPipeline&) = delete;
    GraphicsPipeline& operator=(const GraphicsPipeline&) = delete;

    VkPipeline handle() const { return pipeline_; }
    VkPipelineLayout layout() const { return layout_; }

    void bind(VkCommandBuffer cmd) const;
    // Pushes the descriptors of both stages (a binding both use is written twice with the same data).
    template <class VS, class FS>
    void push_descriptors(VkCommandBuffer cmd, const typename VS::Bindings& vertex,
                          const typename FS::Bindings& fragment) const {
        std::vector<VkWriteDescriptorSet> writes(VS::descriptor_write_count + FS::descriptor_write_count);
        VS::write_descriptors(vertex, writes.data());
        FS::write_descriptors(fragment, writes.data() + VS::descriptor_write_count);
        push_descriptor_writes(cmd, writes);
    }
    // Pushes `push` to every stage that has push constants.
    template <class Push>
    void push_constants(VkCommandBuffer cmd, const Push& push) const {
        static_assert(std::is_trivially_copyable_v<Push>);
        push_constant_bytes(cmd, &push, sizeof(Push));
    }

private:
    void push_descriptor_writes(VkCommandBuffer cmd, std::span<const VkWriteDescriptorSet> writes) const;
    void push_constant_bytes(VkCommandBuffer cmd, const void* data, uint32_t size) const;
    void release();

    VkDevice device_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkPushConstantRange push_range_{};
    PFN_vkCmdPushDescriptorSetKHR push_descriptor_set_ = nullptr;
};

// A raster stage's pipeline, created once per stages::Device on first use and kept by it, like
// the generated compute pipelines: `device.pipeline<RasterPipeline<VS, FS, Describe>>().pipeline`.
// Describe::state() gives its RasterState.
template <class VS, class FS, class Describe>
struct RasterPipeline {
    struct Spec {};

    GraphicsPipeline pipeline;

    static VkResult create(VkDevice device, VkPipelineCache cache, const Spec&, RasterPipeline* out) {
        out->pipeline = GraphicsPipeline::create<VS, FS>(device, cache, Describe::state());
        return VK_SUCCESS;
    }
    void destroy() { pipeline = GraphicsPipeline(); }
};

// Dynamic rendering into whole images that a step declared as attachments
// (Use::color_attachment / Use::depth_attachment put them in the right layouts).
// Clears every attachment to the given values, sets a full-image viewport and scissor.
struct RenderTargets {
    std::vector<ImageView> colors;
    std::vector<VkClearColorValue> clear_colors;  // one per color image
    ImageView depth;                              // none when its image is VK_NULL_HANDLE
    float clear_depth = 1.0f;
};
void begin_rendering(VkCommandBuffer cmd, const RenderTargets& targets);
void end_rendering(VkCommandBuffer cmd);

}  // namespace vplkit
