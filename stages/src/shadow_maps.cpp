#include "vplkit/stages/shadow_maps.hpp"

#include "scene_draws.hpp"
#include "vplkit/error.hpp"
#include "vplkit/graphics_pipeline.hpp"
#include "vplkit/shaders/rsm_raster.hpp"
#include "vplkit/shaders/rsm_shade.hpp"

#include <cstring>
#include <string>

namespace vplkit::stages {
namespace {

namespace vert = shaders::rsm_raster;
namespace frag = shaders::rsm_shade;

struct RsmPipelineDescription {
    static RasterState state() {
        RasterState s;
        s.color_formats = {kRsmPositionFormat, kRsmNormalFormat, kRsmFluxFormat};
        s.depth_format = kShadowDepthFormat;
        s.cull_mode = VK_CULL_MODE_NONE;  // a surface lit from behind still stops and reflects light
        s.depth_compare = VK_COMPARE_OP_LESS;
        return s;
    }
};
using RsmPipeline = ScenePipeline<vert::Module, frag::Module, RsmPipelineDescription>;

}  // namespace

void add_shadow_map_pass(Device& device, StepList& passes, const SceneBuffers& scene, const ShadowMapViews& map,
                         uint32_t index) {
    check_draw_materials(scene, "shadow map");
    check_scene_range(scene, device.limits().max_storage_buffer_range, "shadow map");
    vert::Spec spec{};
    spec.kSceneAddressed = scene.addressed;
    const GraphicsPipeline& pipeline = device.pipeline<RsmPipeline>(spec).pipeline;
    frag::Push scene_push{};
    vert::Bindings geometry;
    bind_scene(device.device(), scene, scene_push, geometry);
    passes.add("shadow map " + std::to_string(index),
               {Use::read(scene.vertices, Stage::vertex), Use::read(scene.indices, Stage::vertex),
                Use::read(scene.materials, Stage::fragment), Use::read(map.light_uniform, Stage::fragment),
                Use::color_attachment(map.position), Use::color_attachment(map.normal), Use::color_attachment(map.flux),
                Use::depth_attachment(map.depth)},
               // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
               [&pipeline, scene, map, geometry, scene_push](VkCommandBuffer cmd) {
                   const VkClearColorValue zero{{0.0f, 0.0f, 0.0f, 0.0f}};
                   begin_rendering(cmd, {{map.position, map.normal, map.flux}, {zero, zero, zero}, map.depth, 1.0f});
                   pipeline.bind(cmd);
                   frag::Bindings material;
                   material.light = map.light_uniform.descriptor();
                   for (const ShadowFace& face : map.faces) {
                       const VkViewport viewport = {float(face.rect.offset.x),
                                                    float(face.rect.offset.y),
                                                    float(face.rect.extent.width),
                                                    float(face.rect.extent.height),
                                                    0.0f,
                                                    1.0f};
                       vkCmdSetViewport(cmd, 0, 1, &viewport);
                       vkCmdSetScissor(cmd, 0, 1, &face.rect);
                       frag::Push push = scene_push;
                       std::memcpy(&push.view_projection, &face.view_projection, sizeof(push.view_projection));
                       push.face_origin = {float(face.rect.offset.x), float(face.rect.offset.y)};
                       draw_scene<vert::Module, frag::Module>(cmd, pipeline, scene, geometry, material, push);
                   }
                   end_rendering(cmd);
               });
}

void add_shadow_map_passes(Device& device, StepList& passes, const SceneBuffers& scene,
                           std::span<const ShadowMapViews> maps) {
    for (size_t i = 0; i < maps.size(); ++i) add_shadow_map_pass(device, passes, scene, maps[i], uint32_t(i));
}

}  // namespace vplkit::stages
