#pragma once
// The scene as the raster stages (G-buffer, shadow maps) bind it: shaders/include/vplkit/raster_scene.glsl
// (vertices, indices) and raster_material.glsl (materials, textures). The runtime's GpuScene
// (vplkit/gpu_scene.hpp) uploads a scene::Scene and converts to SceneBuffers; bring your own
// buffers and sampled images in these layouts otherwise.

#include "vplkit/views.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>

namespace vplkit {

// One draw: a maximal run of consecutive triangles of one material (Scene::triangle_materials),
// so primitive instances of one material that the loader placed one after the other are one draw. Recorded as
// vkCmdDraw(3 * triangle_count, 1, 3 * first_triangle, 0): the vertex shaders pull vertices through the index buffer
// themselves.
struct GpuDraw {
    uint32_t first_triangle = 0;
    uint32_t triangle_count = 0;
    uint32_t material = 0;
};

// The four combined image samplers a draw of one material binds (SHADER_READ_ONLY_OPTIMAL), in
// the order of raster_material.glsl's texture bindings.
struct MaterialTextures {
    VkDescriptorImageInfo base_color{};          // sRGB view, or the white default
    VkDescriptorImageInfo metallic_roughness{};  // UNORM view, or the white default
    VkDescriptorImageInfo normal{};              // UNORM view, or the flat-normal default
    VkDescriptorImageInfo emissive{};            // sRGB view, or the white default (glTF: factor alone)
};

}  // namespace vplkit

namespace vplkit::stages {

// Read only by the raster stages. The textures must already be in SHADER_READ_ONLY_OPTIMAL and
// stay there (they are not declared as uses: no barrier is recorded for them). The two arrays are
// referenced, not copied: they must outlive the recording of the steps.
struct SceneBuffers {
    BufferView vertices;   // scene::Vertex[] (48 bytes each), read by the vertex shaders
    BufferView indices;    // uint32 x 3 per triangle, global vertex indices, read by the vertex shaders
    BufferView materials;  // shaders::SceneMaterial[], one per material, read by the fragment shaders
    std::span<const GpuDraw> draws;
    std::span<const MaterialTextures> textures;  // one per material, indexed by GpuDraw::material
    // Optional: scene::Vertex[] of the pose the previous frame was drawn with (the same triangles,
    // moved), for the G-buffer's motion; empty: nothing moved since (motion 0).
    BufferView previous_vertices;
    // Read vertices, indices and previous vertices at their device addresses, not through
    // bindings (raster_scene.glsl's kSceneAddressed): required when one of them is larger than
    // maxStorageBufferRange (the stages throw otherwise); their buffers then need
    // VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT. Not the default: lavapipe loads through the
    // addresses more slowly. GpuScene sets it when its buffers need it.
    bool addressed = false;
};

}  // namespace vplkit::stages
