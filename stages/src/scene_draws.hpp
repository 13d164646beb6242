#pragma once
// The scene's draws as the raster stages record them (gbuffer.cpp, shadow_maps.cpp): one loop over
// SceneBuffers::draws that pushes a material's descriptors and push constants when the material
// changes, for any pipeline whose fragment shader reads raster_material.glsl.

#include "vplkit/graphics_pipeline.hpp"
#include "vplkit/stages/scene_buffers.hpp"

#include <vulkan/vulkan.h>

#include <cstdint>

namespace vplkit::stages {

// Throws Error naming `stage` when a draw's material has no textures in `scene`.
void check_draw_materials(const SceneBuffers& scene, const char* stage);

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
