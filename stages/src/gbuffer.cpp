#include "vplkit/stages/gbuffer.hpp"

#include "scene_draws.hpp"
#include "vplkit/error.hpp"
#include "vplkit/graphics_pipeline.hpp"
#include "vplkit/shaders/gbuffer_raster.hpp"
#include "vplkit/shaders/gbuffer_shade.hpp"

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

namespace vplkit::stages {
namespace {

namespace vert = shaders::gbuffer_raster;
namespace frag = shaders::gbuffer_shade;

struct GbufferPipelineDescription {
    static RasterState state() {
        RasterState s;
        s.color_formats = {kGbufferPositionFormat, kGbufferNormalFormat,   kGbufferGeometricNormalFormat,
                           kGbufferAlbedoFormat,   kGbufferEmissionFormat, kGbufferMotionFormat};
        s.depth_format = kGbufferDepthFormat;
        s.cull_mode = VK_CULL_MODE_NONE;  // both sides of every triangle: no holes for GI
        s.depth_compare = VK_COMPARE_OP_LESS;
        return s;
    }
};
using GbufferPipeline = ScenePipeline<vert::Module, frag::Module, GbufferPipelineDescription>;

}  // namespace

glm::mat4 vulkan_perspective(float yfov, float aspect, float znear, float zfar) {
    if (!(yfov > 0.0f && yfov < std::numbers::pi_v<float>)) {
        throw Error("camera: vertical field of view " + std::to_string(yfov) + " rad is not in (0, pi)");
    }
    if (!(aspect > 0.0f) || !std::isfinite(aspect))
        throw Error("camera: aspect ratio " + std::to_string(aspect) + " is not positive");
    if (!(znear > 0.0f) || !std::isfinite(znear))
        throw Error("camera: near plane " + std::to_string(znear) + " is not positive");
    if (!(zfar == 0.0f || (zfar > znear && std::isfinite(zfar)))) {
        throw Error("camera: far plane " + std::to_string(zfar) +
                    " is neither 0 (infinite) nor beyond the near plane " + std::to_string(znear));
    }
    const float f = 1.0f / std::tan(0.5f * yfov);
    // clip w = distance in front of the eye (-z); clip z = a z + b with depth z/w = 0 at znear and
    // 1 at zfar: a = -far / (far - near), b = -far near / (far - near); far -> infinity: a = -1, b = -near.
    const float a = zfar == 0.0f ? -1.0f : -zfar / (zfar - znear);
    const float b = zfar == 0.0f ? -znear : -zfar * znear / (zfar - znear);
    glm::mat4 m(0.0f);
    m[0][0] = f / aspect;
    m[1][1] = -f;  // Vulkan's clip-space y points down the image
    m[2][2] = a;
    m[2][3] = -1.0f;
    m[3][2] = b;
    return m;
}

glm::mat4 vulkan_orthographic(float ymag, float aspect, float znear, float zfar) {
    if (!(ymag > 0.0f) || !std::isfinite(ymag))
        throw Error("camera: orthographic half height " + std::to_string(ymag) + " is not positive");
    if (!(aspect > 0.0f) || !std::isfinite(aspect))
        throw Error("camera: aspect ratio " + std::to_string(aspect) + " is not positive");
    if (!(znear >= 0.0f) || !std::isfinite(znear))
        throw Error("camera: near plane " + std::to_string(znear) + " is negative");
    if (!(zfar > znear) || !std::isfinite(zfar)) {
        throw Error("camera: far plane " + std::to_string(zfar) + " is not beyond the near plane " +
                    std::to_string(znear));
    }
    // clip w = 1; depth = (-z - near) / (far - near), 0 at znear, 1 at zfar.
    glm::mat4 m(0.0f);
    m[0][0] = 1.0f / (ymag * aspect);
    m[1][1] = -1.0f / ymag;  // Vulkan's clip-space y points down the image
    m[2][2] = -1.0f / (zfar - znear);
    m[3][2] = -znear / (zfar - znear);
    m[3][3] = 1.0f;
    return m;
}

void add_gbuffer_pass(Device& device, StepList& passes, const SceneBuffers& scene, const CameraView& view,
                      const GbufferViews& images) {
    check_draw_materials(scene, "gbuffer");
    check_scene_range(scene, device.limits().max_storage_buffer_range, "gbuffer");
    if (!images.motion) throw Error("gbuffer: the motion image is missing (gbuffer_views.hpp)");
    const bool moved = bool(scene.previous_vertices);
    if (moved && scene.previous_vertices.size != scene.vertices.size) {
        throw Error("gbuffer: the previous pose's vertices (" + std::to_string(scene.previous_vertices.size) +
                    " bytes) are not the scene's (" + std::to_string(scene.vertices.size) + ")");
    }
    vert::Spec spec{};
    spec.kSceneAddressed = scene.addressed;
    const GraphicsPipeline& pipeline = device.pipeline<GbufferPipeline>(spec).pipeline;
    frag::Push push{};
    push.has_motion = moved ? 1u : 0u;
    std::memcpy(&push.view_projection, &view.view_projection, sizeof(push.view_projection));
    push.viewer_position = {view.position.x, view.position.y, view.position.z};
    // Without a previous pose the current vertices stand in for it (never read: has_motion 0).
    const BufferView& previous = moved ? scene.previous_vertices : scene.vertices;
    vert::Bindings geometry;
    bind_scene(device.device(), scene, push, geometry);
    if (scene.addressed) {
        const VkDeviceAddress address = view_address(device.device(), previous);
        push.previous_vertex_address = {uint32_t(address), uint32_t(address >> 32)};
        geometry.previous_vertices = unread_binding(previous, sizeof(shaders::SceneVertex));
    } else {
        geometry.previous_vertices = previous.descriptor();
    }
    passes.add("gbuffer",
               {Use::read(scene.vertices, Stage::vertex), Use::read(scene.indices, Stage::vertex),
                Use::read(previous, Stage::vertex), Use::read(scene.materials, Stage::fragment),
                Use::color_attachment(images.position), Use::color_attachment(images.normal),
                Use::color_attachment(images.geometric_normal), Use::color_attachment(images.albedo),
                Use::color_attachment(images.emission), Use::color_attachment(images.motion),
                Use::depth_attachment(images.depth)},
               // Views by value: the caller's may be temporaries that are gone when the steps are recorded.
               [&pipeline, scene, geometry, images, push](VkCommandBuffer cmd) {
                   const VkClearColorValue zero{{0.0f, 0.0f, 0.0f, 0.0f}};
                   begin_rendering(cmd, {{images.position, images.normal, images.geometric_normal, images.albedo,
                                          images.emission, images.motion},
                                         {zero, zero, zero, zero, zero, zero},
                                         images.depth,
                                         1.0f});
                   pipeline.bind(cmd);
                   draw_scene<vert::Module, frag::Module>(cmd, pipeline, scene, geometry, {}, push);
                   end_rendering(cmd);
               });
}

}  // namespace vplkit::stages
