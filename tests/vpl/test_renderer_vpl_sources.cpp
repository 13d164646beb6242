// VPL sources from a renderer's own data (stages/renderer_vpl_sources.hpp, renderer_lights.hpp)
// and the scene block (renderer_scene.hpp: BVH and sources in one buffer) against the kit's scene
// loader (upload_vpl_sources, upload_bvh): the same lights, emitters and per-triangle albedo
// traced with the same seed must give the same VPLs bit for bit, with a kind absent
// (no punctual light, no emissive triangle, nothing at all) bound as no buffer. Plus the unit
// helper and the errors.

#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/renderer_scene.hpp"
#include "vplkit/stages/renderer_vpl_sources.hpp"
#include "vplkit/vpl_tracing_buffers.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <cstring>
#include <numbers>
#include <vector>

namespace {

using vplkit::scene::Scene;
using vplkit::stages::RendererEmitter;
using vplkit::stages::RendererLight;
using vplkit::stages::RendererLightKind;

const vplkit::stages::VplTracingOptions kOptions{/*paths=*/1500, /*max_bounces=*/3, /*seed=*/11};

// A closed box, each face its own grey (exact in float: the products below are exact too),
// and with `emitter` a small emissive quad under the ceiling (radiance 2.5, one-sided, facing down).
Scene box_scene(bool emitter) {
    Scene s;
    const glm::vec3 lo{-1.0f, 0.0f, -1.0f}, hi{1.0f, 2.0f, 1.0f};
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    auto material = [&](glm::vec3 rho, glm::vec3 emission) {
        vplkit::scene::Material m;
        m.base_color_factor = glm::vec4(rho, 1.0f);
        m.metallic_factor = 0.0f;
        m.emissive_factor = emission;
        s.materials.push_back(m);
        return uint32_t(s.materials.size() - 1);
    };
    auto triangle = [&](glm::vec3 a, glm::vec3 b, glm::vec3 d, uint32_t m) {
        for (glm::vec3 p : {a, b, d}) {
            vplkit::scene::Vertex v;
            v.position = p;
            v.normal = glm::normalize(glm::cross(b - a, d - a));
            s.indices.push_back(uint32_t(s.vertices.size()));
            s.vertices.push_back(v);
        }
        s.triangle_materials.push_back(m);
        if (s.materials[m].emits()) s.emissive_triangles.push_back(uint32_t(s.triangle_materials.size() - 1));
    };
    const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}};
    for (int f = 0; f < 6; ++f) {
        const uint32_t m = material(glm::vec3(0.25f + 0.125f * f, 0.75f, 0.5f - 0.0625f * f), glm::vec3(0.0f));
        triangle(c[faces[f][0]], c[faces[f][1]], c[faces[f][2]], m);
        triangle(c[faces[f][0]], c[faces[f][2]], c[faces[f][3]], m);
    }
    if (emitter) {
        const uint32_t m = material(glm::vec3(0.5f), glm::vec3(2.5f, 2.0f, 1.5f));
        const float y = 1.75f;  // wound so the front faces down (-y)
        triangle({-0.25f, y, -0.25f}, {0.25f, y, -0.25f}, {0.25f, y, 0.25f}, m);
        triangle({-0.25f, y, -0.25f}, {0.25f, y, 0.25f}, {-0.25f, y, 0.25f}, m);
    }
    return s;
}

std::vector<vplkit::scene::Light> scene_lights() {
    std::vector<vplkit::scene::Light> lights(3);
    lights[0].type = vplkit::scene::LightType::point;
    lights[0].position = {0.25f, 1.5f, -0.25f};
    lights[0].color = {1.0f, 0.5f, 0.25f};
    lights[0].intensity = 4.0f;
    lights[1].type = vplkit::scene::LightType::spot;
    lights[1].position = {-0.5f, 1.875f, 0.5f};
    lights[1].direction = {0.0f, -1.0f, 0.0f};
    lights[1].inner_cone_angle = 0.25f;
    lights[1].outer_cone_angle = 0.75f;
    lights[1].range = 3.0f;
    lights[1].intensity = 6.0f;
    lights[2].type = vplkit::scene::LightType::directional;  // outside the box: hits its outer faces
    lights[2].direction = {0.0f, 0.0f, -1.0f};
    lights[2].color = {0.5f, 1.0f, 1.0f};
    lights[2].intensity = 2.0f;
    return lights;
}

// The same lights as a renderer states them: colour x strength in one radiometric intensity.
std::vector<RendererLight> renderer_lights(const std::vector<vplkit::scene::Light>& lights) {
    std::vector<RendererLight> out;
    for (const auto& l : lights) {
        RendererLight r;
        r.kind = RendererLightKind(uint32_t(l.type));
        r.position = l.position;
        r.direction = l.direction;
        r.intensity = l.color * l.intensity;
        r.range = l.range;
        r.inner_cone_angle = l.inner_cone_angle;
        r.outer_cone_angle = l.outer_cone_angle;
        out.push_back(r);
    }
    return out;
}

struct Traced {
    std::vector<vplkit::shaders::Vpl> vpls;
    std::vector<uint32_t> bounces;
};

Traced trace(const vplkit::stages::BvhBuffers& bvh, const vplkit::stages::VplSourceBuffers& sources) {
    vplkit::Context& ctx = vplkit::test::context();
    auto output = vplkit::VplTracingOutput::create(ctx, kOptions);
    vplkit::PassList passes("renderer vpl sources test");
    vplkit::stages::add_trace_vpls_passes(ctx, passes, bvh, sources, kOptions, output);
    passes.run(ctx);
    const uint32_t count = vplkit::download_vpl_count(output);
    Traced t;
    if (count > 0) {
        t.vpls = output.vpls.download<vplkit::shaders::Vpl>(count);
        t.bounces = output.bounces.download<uint32_t>(count);
    }
    return t;
}

void check_same(const Traced& got, const Traced& expected) {
    REQUIRE(got.vpls.size() == expected.vpls.size());
    CHECK(got.bounces == expected.bounces);
    // Field by field: the padding between a Vpl's vec3s is not written by the shader.
    size_t differing = 0;
    for (size_t i = 0; i < got.vpls.size(); ++i) {
        const vplkit::shaders::Vpl &g = got.vpls[i], &e = expected.vpls[i];
        for (auto member :
             {&vplkit::shaders::Vpl::position, &vplkit::shaders::Vpl::normal, &vplkit::shaders::Vpl::flux}) {
            differing += std::memcmp(&(g.*member), &(e.*member), sizeof(g.*member)) != 0;
        }
    }
    CHECK(differing == 0);
}

// The scene traced through the loader's sources and through the renderer's (its sources beside
// the loader's BVH, and renderer_scene's BVH and sources in one block); returns the VPL count.
size_t check_same_vpls(const Scene& scene, const std::vector<RendererEmitter>& emitters) {
    vplkit::Context& ctx = vplkit::test::context();
    const std::vector<glm::vec3> triangles = vplkit::scene::triangle_positions(scene);
    const vplkit::GpuBvh bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(triangles));
    const auto loader = vplkit::upload_vpl_sources(ctx, scene);
    const Traced expected = trace(bvh, loader);

    std::vector<glm::vec3> albedo;
    for (uint32_t m : scene.triangle_materials) albedo.push_back(glm::vec3(scene.materials[m].base_color_factor));
    const std::vector<RendererLight> lights = renderer_lights(scene.lights);
    const auto data = vplkit::stages::vpl_sources_from_renderer(lights, emitters, {triangles, albedo});
    CHECK(data.lights.size() == scene.lights.size());
    CHECK(data.emissive.size() == scene.emissive_triangles.size());
    CHECK(glm::vec3(data.total_power) == loader.total_power);
    std::vector<uint8_t> bytes(data.bytes());
    data.write(bytes.data());
    auto block = vplkit::Buffer::create(ctx, bytes.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vplkit::MemoryUse::device, "renderer sources");
    block.upload(bytes);
    const vplkit::stages::VplSourceBuffers views = data.views(block);
    CHECK(bool(views.lights) == !lights.empty());
    CHECK(bool(views.emissive) == !emitters.empty());
    const Traced got = trace(bvh, views);
    check_same(got, expected);

    // The BVH and the sources in one block (renderer_scene), placed at an offset in a buffer.
    const vplkit::stages::RendererSceneData scene_data =
        vplkit::stages::renderer_scene(lights, emitters, {triangles, albedo});
    constexpr VkDeviceSize kAt = 512;
    std::vector<uint8_t> scene_bytes(kAt + scene_data.bytes(), 0xAB);
    scene_data.write(scene_bytes.data() + kAt);
    auto scene_buffer = vplkit::Buffer::create(ctx, scene_bytes.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                               vplkit::MemoryUse::device, "renderer scene");
    scene_buffer.upload(scene_bytes);
    const vplkit::BufferView scene_block{scene_buffer.handle(), kAt, scene_data.bytes(), "renderer scene"};
    const vplkit::stages::RendererSceneBuffers scene_views = scene_data.views(scene_block);
    CHECK(scene_views.bvh.node_count == vplkit::stages::BvhBuffers(bvh).node_count);
    CHECK(scene_views.bvh.scene_scale == vplkit::stages::BvhBuffers(bvh).scene_scale);
    check_same(trace(scene_views.bvh, scene_views.sources), expected);
    vplkit::BufferView short_block = scene_block;
    short_block.size -= 1;
    CHECK_THROWS_WITH_AS(scene_data.views(short_block), doctest::Contains("the scene needs"), vplkit::Error);
    return got.vpls.size();
}

const std::vector<RendererEmitter> kCeilingEmitter = {{12, {2.5f, 2.0f, 1.5f}, false}, {13, {2.5f, 2.0f, 1.5f}, false}};

}  // namespace

TEST_CASE("renderer VPL sources: lights, an emitter and per-triangle albedo trace as the scene loader's") {
    Scene scene = box_scene(true);
    scene.lights = scene_lights();
    CHECK(check_same_vpls(scene, kCeilingEmitter) > 1000);
}

TEST_CASE("renderer VPL sources: a kind that is absent needs no buffer") {
    SUBCASE("punctual lights, no emissive triangle") {
        Scene scene = box_scene(false);
        scene.lights = scene_lights();
        CHECK(check_same_vpls(scene, {}) > 1000);
    }
    SUBCASE("an emissive triangle, no punctual light") {
        Scene scene = box_scene(true);
        CHECK(check_same_vpls(scene, kCeilingEmitter) > 1000);
    }
    SUBCASE("nothing emits: no VPL") {
        vplkit::Context& ctx = vplkit::test::context();
        const std::vector<glm::vec3> triangles = vplkit::scene::triangle_positions(box_scene(false));
        const vplkit::GpuBvh bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(triangles));
        const auto data = vplkit::stages::vpl_sources_from_renderer({}, {}, {triangles, {}, glm::vec3(0.5f)});
        CHECK(data.emitter_count == 0);
        CHECK(data.emitter_cdf.empty());
        auto block = vplkit::Buffer::create(ctx, data.bytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        std::vector<uint8_t> bytes(data.bytes());
        data.write(bytes.data());
        block.upload(bytes);
        CHECK(trace(bvh, data.views(block)).vpls.empty());
    }
}

TEST_CASE("renderer VPL sources: one albedo for all triangles is that albedo per triangle") {
    const std::vector<glm::vec3> triangles = vplkit::scene::triangle_positions(box_scene(false));
    const std::vector<glm::vec3> each(triangles.size() / 3, glm::vec3(0.25f, 0.5f, 0.75f));
    const auto lights = renderer_lights(scene_lights());
    const auto constant = vplkit::stages::vpl_sources_from_renderer(lights, {}, {triangles, {}, each[0]});
    const auto per_triangle = vplkit::stages::vpl_sources_from_renderer(lights, {}, {triangles, each});
    REQUIRE(constant.triangle_albedo.size() == each.size());
    std::vector<uint8_t> a(constant.bytes()), b(per_triangle.bytes());
    constant.write(a.data());
    per_triangle.write(b.data());
    CHECK(a == b);
}

TEST_CASE("renderer VPL sources: a texture's mean albedo is the scene loader's") {
    // The loader's reflectance of a material with a base colour texture (factor 1, not metallic)
    // is the texture's mean linear colour: the helper must give the same floats.
    vplkit::Context& ctx = vplkit::test::context();
    const std::vector<uint8_t> texels = {255, 0,   64,  255, 128, 255, 64, 10,  3,   77, 200, 255,
                                         90,  180, 250, 0,   17,  33,  99, 255, 240, 1,  128, 255};
    Scene scene = box_scene(false);
    vplkit::scene::Image image;
    image.width = 3;
    image.height = 2;
    image.rgba = texels;
    image.srgb = true;
    scene.images = {image};
    scene.textures.resize(1);
    for (auto& m : scene.materials) {
        m.base_color_factor = glm::vec4(1.0f);
        m.base_color_texture = 0;
    }
    scene.lights = scene_lights();
    const auto loader = vplkit::upload_vpl_sources(ctx, scene);
    const auto rho = loader.triangle_albedo.download<vplkit::shaders::vec4>(scene.triangle_materials.size());
    const glm::vec3 mean = vplkit::stages::mean_texture_albedo(texels, 3, 2, /*srgb=*/true);
    CHECK(rho[0].x == mean.x);
    CHECK(rho[0].y == mean.y);
    CHECK(rho[0].z == mean.z);
    // Linear texels are averaged as they are.
    const glm::vec3 plain = vplkit::stages::mean_texture_albedo(texels, 3, 2, /*srgb=*/false);
    CHECK(plain.x == doctest::Approx((255 + 128 + 3 + 90 + 17 + 240) / 6.0 / 255.0).epsilon(1e-6));
    CHECK(plain.x > mean.x);  // decoding sRGB darkens the mid tones
    CHECK_THROWS_WITH_AS(vplkit::stages::mean_texture_albedo(texels, 4, 2, true),
                         doctest::Contains("a 4x2 texture needs 32 bytes (RGBA8), got 24"), vplkit::Error);
}

TEST_CASE("renderer lights: albedo * N.L shading needs pi times the intensity") {
    // Radiance off a Lambertian surface of albedo a under a sun at angle theta: the renderer's
    // a * cos * L, the kit's a / pi * cos * E (vplkit/brdf.glsl) with E the converted light.
    const glm::vec3 light{0.5f, 2.0f, 3.0f}, albedo{0.8f, 0.5f, 0.25f};
    const float cos_theta = 0.6f;
    const glm::vec3 kit_e = vplkit::stages::radiometric_from_albedo_ndotl(light);
    const glm::vec3 kit = albedo / std::numbers::pi_v<float> * cos_theta * kit_e;
    const glm::vec3 renderer = albedo * cos_theta * light;
    for (int c = 0; c < 3; ++c) CHECK(kit[c] == doctest::Approx(renderer[c]).epsilon(1e-6));
}

TEST_CASE("renderer VPL sources: bad input is refused with its reason") {
    vplkit::Context& ctx = vplkit::test::context();
    const std::vector<glm::vec3> triangles = vplkit::scene::triangle_positions(box_scene(false));
    const std::vector<glm::vec3> two_albedos(2, glm::vec3(0.5f));
    using vplkit::stages::vpl_sources_from_renderer;
    CHECK_THROWS_WITH_AS(vpl_sources_from_renderer({}, {}, {triangles, two_albedos}),
                         doctest::Contains("2 albedos for 12 triangles"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vpl_sources_from_renderer({}, {}, {triangles, {}, glm::vec3(1.5f)}),
                         doctest::Contains("albedo of triangle 0 is not in [0, 1]"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vpl_sources_from_renderer({}, {}, {std::span(triangles).first(4)}),
                         doctest::Contains("need 3 each"), vplkit::Error);
    RendererLight tilted;
    tilted.kind = RendererLightKind::directional;
    tilted.direction = {0.0f, -2.0f, 0.0f};
    CHECK_THROWS_WITH_AS(vpl_sources_from_renderer(std::span(&tilted, 1), {}, {triangles}),
                         doctest::Contains("light 0: direction must be a unit vector"), vplkit::Error);
    const RendererEmitter outside{12, glm::vec3(1.0f), false};
    CHECK_THROWS_WITH_AS(vpl_sources_from_renderer({}, std::span(&outside, 1), {triangles}),
                         doctest::Contains("emitter 0 names triangle 12 of 12"), vplkit::Error);

    // A count with no buffer behind it.
    const auto data = vpl_sources_from_renderer(renderer_lights(scene_lights()), {}, {triangles});
    auto block = vplkit::Buffer::create(ctx, data.bytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vplkit::MemoryUse::device, "sources");
    CHECK_THROWS_WITH_AS(data.views(vplkit::BufferView{block.handle(), 0, 64, "small"}),
                         doctest::Contains("'small' holds 64 bytes"), vplkit::Error);
    vplkit::stages::VplSourceBuffers views = data.views(block);
    views.lights = {};
    const vplkit::GpuBvh bvh = vplkit::upload_bvh(ctx, vplkit::build_bvh(triangles));
    auto output = vplkit::VplTracingOutput::create(ctx, kOptions);
    vplkit::PassList passes;
    CHECK_THROWS_WITH_AS(vplkit::stages::add_trace_vpls_passes(ctx, passes, bvh, views, kOptions, output),
                         doctest::Contains("lights buffer '' holds fewer than 3 records"), vplkit::Error);
}
