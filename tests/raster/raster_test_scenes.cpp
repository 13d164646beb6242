#include "raster_test_scenes.hpp"

#include "vplkit/camera_view.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/stages/gbuffer.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include <filesystem>
#include <utility>

namespace raster_test {

using namespace vplkit::scene;

void add_quad(Scene& scene, const std::array<glm::vec3, 4>& corners, const std::array<glm::vec2, 4>& uvs,
              uint32_t material, const std::optional<std::array<glm::vec3, 4>>& normals) {
    const glm::vec3 face = glm::normalize(glm::cross(corners[1] - corners[0], corners[2] - corners[0]));
    // dP/du from the triangle (a, b, c): solve [e1 e2] = [dP/du dP/dv] [duv1 duv2].
    const glm::vec3 e1 = corners[1] - corners[0], e2 = corners[2] - corners[0];
    const glm::vec2 d1 = uvs[1] - uvs[0], d2 = uvs[2] - uvs[0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    const glm::vec3 dpdu = glm::normalize((e1 * d2.y - e2 * d1.y) / det);
    const uint32_t first = uint32_t(scene.vertices.size());
    for (int k = 0; k < 4; ++k) {
        Vertex v;
        v.position = corners[k];
        v.normal = normals ? glm::normalize((*normals)[k]) : face;
        v.tangent = glm::vec4(glm::normalize(dpdu - v.normal * glm::dot(v.normal, dpdu)), 1.0f);
        v.uv0 = uvs[k];
        scene.vertices.push_back(v);
    }
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) scene.indices.push_back(first + i);
    scene.triangle_materials.push_back(material);
    scene.triangle_materials.push_back(material);
}

int32_t add_texture(Scene& scene, uint32_t width, uint32_t height, std::vector<uint8_t> rgba, bool srgb, bool linear) {
    Image image;
    image.name = "test image " + std::to_string(scene.images.size());
    image.width = width;
    image.height = height;
    image.rgba = std::move(rgba);
    image.srgb = srgb;
    image.linear = linear;
    scene.images.push_back(std::move(image));
    Texture texture;
    texture.image = uint32_t(scene.images.size() - 1);
    texture.sampler = {Wrap::repeat, Wrap::repeat, Filter::nearest, Filter::nearest, MipmapMode::none};
    scene.textures.push_back(texture);
    return int32_t(scene.textures.size() - 1);
}

namespace {

// uv (0,0) at the first corner, u along the second... for a quad given as top-left, bottom-left,
// bottom-right, top-right (counter-clockwise seen from +z when y is up).
constexpr std::array<glm::vec2, 4> kUvTlBlBrTr = {glm::vec2(0, 0), glm::vec2(0, 1), glm::vec2(1, 1), glm::vec2(1, 0)};

void finish(Scene& scene) {
    scene.bounds.min = scene.bounds.max = scene.vertices.front().position;
    for (const Vertex& v : scene.vertices) {
        scene.bounds.min = glm::min(scene.bounds.min, v.position);
        scene.bounds.max = glm::max(scene.bounds.max, v.position);
    }
}

}  // namespace

Scene gbuffer_scene(float scale) {
    Scene s;
    s.source = "raster test scene";
    // Quadrant colours (sRGB) with one quadrant's alpha at 90/255 (read by the blended material).
    const int32_t quadrants = add_texture(s, 2, 2,
                                          {200, 30, 90, 255, 20, 180, 250, 255,  //
                                           255, 255, 0, 90, 100, 100, 100, 255},
                                          true, false);
    // Metallic-roughness: G roughness, B metallic per quadrant.
    const int32_t metal_rough = add_texture(s, 2, 2,
                                            {0, 40, 200, 255, 0, 120, 10, 255,  //
                                             0, 250, 128, 255, 0, 5, 77, 255},
                                            false, true);
    // Alpha checker for the mask material: 255, 0 / 100, 255.
    const int32_t checker = add_texture(s, 2, 2,
                                        {250, 250, 250, 255, 10, 10, 10, 0,  //
                                         60, 200, 60, 100, 200, 60, 60, 255},
                                        true, false);
    const int32_t normal_map = add_texture(s, 1, 1, {200, 90, 220, 255}, false, true);

    Material wall;
    wall.name = "wall";
    wall.base_color_factor = {0.8f, 0.6f, 0.4f, 1.0f};
    wall.metallic_factor = 0.25f;
    wall.roughness_factor = 0.75f;
    Material textured;
    textured.name = "textured";
    textured.base_color_texture = quadrants;
    textured.metallic_roughness_texture = metal_rough;
    Material emissive;
    emissive.name = "emissive back face";
    emissive.base_color_factor = {0.3f, 0.3f, 0.9f, 1.0f};
    emissive.emissive_factor = {2.0f, 1.0f, 0.5f};
    emissive.emissive_strength = 1.5f;
    emissive.emissive_texture = checker;
    emissive.metallic_factor = 0.0f;
    emissive.roughness_factor = 0.5f;
    Material mask;
    mask.name = "mask";
    mask.base_color_texture = checker;
    mask.alpha_mode = AlphaMode::mask;
    mask.alpha_cutoff = 0.3f;
    mask.metallic_factor = 0.0f;
    Material mapped;
    mapped.name = "normal mapped, blended";
    mapped.base_color_texture = quadrants;
    mapped.normal_texture = normal_map;
    mapped.normal_scale = 0.8f;
    mapped.alpha_mode = AlphaMode::blend;
    mapped.double_sided = true;
    mapped.metallic_factor = 0.5f;
    mapped.roughness_factor = 0.3f;
    s.materials = {wall, textured, emissive, mask, mapped};

    // 0: the wall behind everything, with tilted vertex normals (interpolated, then normalized).
    add_quad(s,
             {glm::vec3(-1.5f, 1.5f, -1.0f), glm::vec3(-1.5f, -1.5f, -1.0f), glm::vec3(1.5f, -1.5f, -1.0f),
              glm::vec3(1.5f, 1.5f, -1.0f)},
             kUvTlBlBrTr, 0,
             std::array<glm::vec3, 4>{glm::vec3(-0.3f, 0.2f, 1.0f), glm::vec3(-0.2f, -0.3f, 1.0f),
                                      glm::vec3(0.3f, -0.1f, 1.0f), glm::vec3(0.1f, 0.3f, 1.0f)});
    // 1: textured quad facing the camera.
    add_quad(s,
             {glm::vec3(-1.2f, 1.2f, 0.0f), glm::vec3(-1.2f, 0.1f, 0.0f), glm::vec3(-0.1f, 0.1f, 0.0f),
              glm::vec3(-0.1f, 1.2f, 0.0f)},
             kUvTlBlBrTr, 1);
    // 2: single-sided quad seen from behind (its front faces -z): drawn, normals turned to the eye.
    add_quad(s,
             {glm::vec3(0.2f, 1.1f, 0.2f), glm::vec3(1.1f, 1.1f, 0.2f), glm::vec3(1.1f, 0.2f, 0.2f),
              glm::vec3(0.2f, 0.2f, 0.2f)},
             {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}, 2);
    // 3: alpha-masked quad in front of the tilted one (its holes show what is behind).
    add_quad(s,
             {glm::vec3(-1.0f, -0.2f, 0.5f), glm::vec3(-1.0f, -1.1f, 0.5f), glm::vec3(0.4f, -1.1f, 0.5f),
              glm::vec3(0.4f, -0.2f, 0.5f)},
             kUvTlBlBrTr, 3);
    // 4: tilted normal-mapped quad (perspective-correct interpolation moves its texel borders).
    add_quad(s,
             {glm::vec3(0.1f, -0.2f, 0.3f), glm::vec3(0.1f, -1.2f, 0.3f), glm::vec3(1.2f, -1.2f, -0.5f),
              glm::vec3(1.2f, -0.2f, -0.5f)},
             kUvTlBlBrTr, 4);
    for (Vertex& v : s.vertices) v.position *= scale;
    finish(s);
    return s;
}

Scene floor_scene(float half, glm::vec3 albedo) {
    Scene s;
    s.source = "raster test floor";
    Material m;
    m.name = "floor";
    m.base_color_factor = glm::vec4(albedo, 1.0f);
    m.metallic_factor = 0.0f;
    s.materials = {m};
    // Counter-clockwise seen from +y.
    add_quad(s,
             {glm::vec3(-half, 0.0f, -half), glm::vec3(-half, 0.0f, half), glm::vec3(half, 0.0f, half),
              glm::vec3(half, 0.0f, -half)},
             kUvTlBlBrTr, 0);
    finish(s);
    return s;
}

RolledCornellGbuffer rolled_cornell_gbuffer(vplkit::Context& ctx, uint32_t width, uint32_t height) {
    const auto path = std::filesystem::path(VPLKIT_SOURCE_DIR) / "scenes/cornell_point/cornell_point.gltf";
    const Scene scene = vplkit::scene::load_gltf(path);
    const vplkit::scene::Camera& file_camera = scene.camera();
    vplkit::scene::Camera camera =
        vplkit::scene::look_at(file_camera.position + glm::vec3(0.4f, 0.3f, 0.0f), scene.bounds.center(),
                               glm::normalize(glm::vec3(0.15f, 1.0f, 0.0f)), file_camera.yfov);
    camera.znear = file_camera.znear;
    camera.zfar = file_camera.zfar;
    RolledCornellGbuffer out;
    out.view = vplkit::camera_view(camera, width, height);
    out.view_to_world = glm::mat3(camera.world_from_camera());
    out.bounds_min = scene.bounds.min;
    out.bounds_max = scene.bounds.max;
    auto gpu = vplkit::GpuScene::create(ctx, scene);
    auto images = vplkit::GbufferImages::create(ctx, width, height);
    vplkit::PassList passes("raster test: the rolled Cornell box's gbuffer");
    vplkit::stages::add_gbuffer_pass(ctx, passes, gpu, out.view, images);
    passes.run(ctx);
    out.position = download_rgba(images.position);
    out.normal = download_rgba(images.normal);
    out.geometric_normal = download_rgba(images.geometric_normal);
    out.albedo = download_rgba(images.albedo);
    out.depth = images.depth.download<float>();
    return out;
}

std::vector<glm::vec4> download_rgba(vplkit::Image& image) {
    if (image.format() == VK_FORMAT_R32G32B32A32_SFLOAT) return image.download<glm::vec4>();
    if (image.format() != VK_FORMAT_R16G16B16A16_SFLOAT) throw std::runtime_error("download_rgba: unexpected format");
    const std::vector<uint16_t> halves = image.download<uint16_t>();
    std::vector<glm::vec4> out(halves.size() / 4);
    for (size_t i = 0; i < out.size(); ++i) {
        for (int c = 0; c < 4; ++c) out[i][c] = glm::unpackHalf1x16(halves[4 * i + c]);
    }
    return out;
}

}  // namespace raster_test
