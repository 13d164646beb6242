#pragma once
// The scene's draws as the raster stages record them (gbuffer.cpp, shadow_maps.cpp): one loop over
// SceneBuffers::draws that pushes a material's descriptors and push constants when the material
// changes, for any pipeline whose fragment shader reads raster_material.glsl.

#include "vplkit/graphics_pipeline.hpp"
#include "vplkit/stages/scene_buffers.hpp"

#include <vulkan/vulkan.h>

#include "vplkit/shaders/types.hpp"

#include <algorithm>
#include <cstdint>

namespace vplkit::stages {

// Throws Error naming `stage` when a draw's material has no textures in `scene`.
void check_draw_materials(const SceneBuffers& scene, const char* stage);

// Throws Error naming `stage`, the buffer and the limit when `scene` is not `addressed` and one
// of its vertex, index or previous-vertex views is larger than a storage binding may be.
void check_scene_range(const SceneBuffers& scene, uint64_t max_storage_buffer_range, const char* stage);

// The device address of the view's first byte.
VkDeviceAddress view_address(VkDevice device, const BufferView& view);

// A raster stage's pipeline specialized by its vertex shader's Spec (raster_scene.glsl's
// kSceneAddressed), created once per stages::Device for each Spec, like RasterPipeline.
template <class VS, class FS, class Describe>
struct ScenePipeline {
    using Spec = typename VS::Spec;

    GraphicsPipeline pipeline;

    static VkResult create(VkDevice device, VkPipelineCache cache, const Spec& spec, ScenePipeline* out) {
        out->pipeline = GraphicsPipeline::create<VS, FS>(device, cache, Describe::state(), spec);
        return VK_SUCCESS;
    }
    void destroy() { pipeline = GraphicsPipeline(); }
};

// A binding that names `view`'s buffer, for an addressed scene (nothing reads it): at the buffer's
// start, so that no view offset needs minStorageBufferOffsetAlignment, at most `record` bytes.
inline VkDescriptorBufferInfo unread_binding(const BufferView& view, VkDeviceSize record) {
    return {view.buffer, 0, std::min(view.offset + view.size, record)};
}

// Fills raster_scene.glsl's push fields and bindings of `scene`: an `addressed` scene's addresses
// and counts, and bindings one record wide (every binding must be filled; nothing reads them);
// else whole-buffer bindings and zero addresses.
template <class Push, class Bindings>
void bind_scene(VkDevice device, const SceneBuffers& scene, Push& push, Bindings& geometry) {
    constexpr VkDeviceSize kVertexBytes = sizeof(shaders::SceneVertex);
    if (scene.addressed) {
        const VkDeviceAddress vertices = view_address(device, scene.vertices);
        const VkDeviceAddress indices = view_address(device, scene.indices);
        push.scene_vertex_address = {uint32_t(vertices), uint32_t(vertices >> 32)};
        push.scene_index_address = {uint32_t(indices), uint32_t(indices >> 32)};
        push.scene_vertex_count = uint32_t(scene.vertices.size / kVertexBytes);
        push.scene_index_count = uint32_t(scene.indices.size / sizeof(uint32_t));
        geometry.scene_vertices = unread_binding(scene.vertices, kVertexBytes);
        geometry.scene_indices = unread_binding(scene.indices, sizeof(uint32_t));
    } else {
        geometry.scene_vertices = scene.vertices.descriptor();
        geometry.scene_indices = scene.indices.descriptor();
    }
}

// Records every draw of `scene` with `pipeline` (bound, inside a rendering begun by the caller).
// `material` comes with the fragment shader's other bindings filled in; its material fields, and
// `push.material`, are set per draw. Draws that follow one of the same material push nothing.
template <class Vert, class Frag, class Push>
void draw_scene(VkCommandBuffer cmd, const GraphicsPipeline& pipeline, const SceneBuffers& scene,
                const typename Vert::Bindings& geometry, typename Frag::Bindings material, Push push) {
    uint32_t bound_material = UINT32_MAX;
    for (const GpuDraw& draw : scene.draws) {
        if (draw.material != bound_material) {
            const MaterialTextures& textures = scene.textures[draw.material];
            material.scene_materials = scene.materials.descriptor();
            material.base_color_texture = textures.base_color;
            material.metallic_roughness_texture = textures.metallic_roughness;
            material.normal_texture = textures.normal;
            material.emissive_texture = textures.emissive;
            pipeline.push_descriptors<Vert, Frag>(cmd, geometry, material);
            push.material = draw.material;
            pipeline.push_constants(cmd, push);
            bound_material = draw.material;
        }
        vkCmdDraw(cmd, 3 * draw.triangle_count, 1, 3 * draw.first_triangle, 0);
    }
}

}  // namespace vplkit::stages
