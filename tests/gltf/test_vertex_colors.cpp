// COLOR_0 (glTF 2.0 3.9.2: it multiplies the base colour) from the loader through the G-buffer's
// albedo and the per-triangle albedo light paths read at their hits (trace_vpls.comp).
//
// Expectation: feature_files' vertex_colors quad (corners red, green, blue, white; base colour
// factor 0.5) interpolated linearly over its two triangles at the world position the G-buffer
// stored for each pixel. Tolerances: loader 1e-6 (normalized integers decode exactly up to float
// rounding); G-buffer 2e-3 absolute (RGBA16F albedo: ~5e-4 relative, plus the interpolation of the
// colour and of the position at float precision); VPL albedo 1e-6 (host arithmetic).

#include "feature_files.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/vpl_tracing_buffers.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/gtc/packing.hpp>

#include <cmath>
#include <cstring>

namespace {

using scene_test::kFloat;
using scene_test::kUnsignedByte;
using scene_test::kUnsignedShort;

// The colour the file gives at (x, y) on the quad (z = 0): triangles (0,1,2) and (0,2,3).
glm::vec3 quad_color(double x, double y) {
    const glm::dvec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1), white(1, 1, 1);
    if (y <= x) return glm::vec3((1.0 - x) * red + (x - y) * green + y * blue);
    return glm::vec3((1.0 - y) * red + x * blue + (y - x) * white);
}

vplkit::scene::Scene load(const gltf_features::GltfBuilder& b, const std::string& name) {
    scene_test::TempDir dir(name);
    return vplkit::scene::load_gltf(b.write(dir.path(), name, true));
}

}  // namespace

TEST_CASE("gltf: COLOR_0 as float, normalized unsigned byte and short, RGB and RGBA is read per vertex") {
    struct Case {
        int type;
        bool rgba;
    };
    for (const Case c : {Case{kFloat, false}, Case{kFloat, true}, Case{kUnsignedByte, false}, Case{kUnsignedByte, true},
                         Case{kUnsignedShort, false}, Case{kUnsignedShort, true}}) {
        CAPTURE(c.type);
        CAPTURE(c.rgba);
        const auto scene = load(gltf_features::vertex_colors(c.type, c.rgba), "colors");
        CHECK(vplkit::scene::warning_lines(scene.warnings).empty());
        REQUIRE(scene.vertices.size() == 4);
        const glm::vec4 expected[4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
        for (int v = 0; v < 4; ++v) {
            for (int k = 0; k < 4; ++k) CHECK(std::abs(scene.vertices[size_t(v)].color[k] - expected[v][k]) <= 1e-6f);
        }
    }
    // Without COLOR_0 every vertex is white (the base colour alone).
    scene_test::GltfBuilder plain;
    plain.roots.push_back(
        plain.node("{\"mesh\":" + std::to_string(plain.mesh("[" + scene_test::unit_quad(plain) + "]")) + "}"));
    const auto scene = load(plain, "plain");
    for (const auto& v : scene.vertices) CHECK(v.color == glm::vec4(1.0f));
}

TEST_CASE("gltf: vertex colours reach the G-buffer's albedo") {
    auto& ctx = vplkit::test::context();
    const auto scene = load(gltf_features::vertex_colors(kUnsignedByte, false), "gbuffer_colors");
    constexpr uint32_t kSize = 32;
    auto gpu = vplkit::GpuScene::create(ctx, scene);
    auto images = vplkit::GbufferImages::create(ctx, kSize, kSize);
    vplkit::PassList passes("vertex colour test");
    vplkit::stages::add_gbuffer_pass(ctx, passes, gpu, vplkit::camera_view(scene.camera(), kSize, kSize), images);
    passes.run(ctx);
    const auto position = images.position.download<glm::vec4>();
    const auto albedo_half = images.albedo.download<uint16_t>();
    uint32_t covered = 0;
    double worst = 0.0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
        if (position[i].w != 1.0f) continue;
        ++covered;
        const glm::vec3 expected = 0.5f * quad_color(position[i].x, position[i].y);
        for (int c = 0; c < 3; ++c) {
            const float got = glm::unpackHalf1x16(albedo_half[4 * i + size_t(c)]);
            worst = std::max(worst, double(std::abs(got - expected[c])));
        }
    }
    CHECK(covered > kSize * kSize / 4);
    CHECK(worst <= 2e-3);
}

TEST_CASE("gltf: vertex colours reach the albedo light paths read at a hit (mean of the triangle's corners)") {
    auto& ctx = vplkit::test::context();
    const auto scene = load(gltf_features::vertex_colors(kFloat, true), "vpl_colors");
    const auto sources = vplkit::upload_vpl_sources(ctx, scene);
    const auto albedo = sources.triangle_albedo.template download<vplkit::shaders::vec4>(2);
    // Triangle 0: red, green, blue; triangle 1: red, blue, white (x 0.5, metallic 0).
    const glm::vec3 expected[2] = {glm::vec3(1, 1, 1) / 3.0f * 0.5f, glm::vec3(2, 1, 2) / 3.0f * 0.5f};
    for (int t = 0; t < 2; ++t) {
        CHECK(std::abs(albedo[size_t(t)].x - expected[t].x) <= 1e-6f);
        CHECK(std::abs(albedo[size_t(t)].y - expected[t].y) <= 1e-6f);
        CHECK(std::abs(albedo[size_t(t)].z - expected[t].z) <= 1e-6f);
    }
}
