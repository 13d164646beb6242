// An `addressed` scene (stages::SceneBuffers::addressed) is read by the raster stages at its
// device addresses (raster_scene.glsl's kSceneAddressed), not through bindings: what vertices past
// maxStorageBufferRange take (the 4.32M-triangle room's 2.17M), tested here without such a scene
// by forcing the path on the in-repo Cornell box. Vertices, indices and the previous pose placed
// at unaligned offsets inside larger buffers full of decoys give the binding path's G-buffer
// (motion included) and shadow map bit for bit; a scene past the range that is not addressed is
// refused, naming the buffer and the limit.

#include "raster_test_scenes.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/shadow_map.hpp"
#include "vplkit_test/context.hpp"
#include "vplkit_test/range_refusal.hpp"
#include "vplkit_test/placed_buffer.hpp"

#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using vplkit::test::placed;

vplkit::scene::Scene cornell() {
    return vplkit::scene::load_gltf(std::filesystem::path(VPLKIT_SOURCE_DIR) /
                                    "scenes/cornell_point/cornell_point.gltf");
}

// A decoy vertex far outside the box, so reading it moves a triangle across the image.
vplkit::scene::Vertex decoy_vertex() {
    vplkit::scene::Vertex v{};
    v.position = {1e3f, -1e3f, 1e3f};
    v.normal = {0.0f, 0.0f, 1.0f};
    v.color = {1.0f, 0.0f, 1.0f, 1.0f};
    return v;
}

struct GbufferBytes {
    std::vector<std::vector<glm::vec4>> colours;  // position, normal, geometric normal, albedo, emission, motion
    std::vector<float> depth;
};

GbufferBytes render_gbuffer(const vplkit::stages::SceneBuffers& scene, const vplkit::stages::CameraView& view) {
    vplkit::Context& ctx = vplkit::test::context();
    auto images = vplkit::GbufferImages::create(ctx, 64, 64);
    vplkit::PassList passes("scene address gbuffer");
    vplkit::stages::add_gbuffer_pass(ctx, passes, scene, view, images);
    passes.run(ctx);
    GbufferBytes r;
    for (vplkit::Image* image : {&images.position, &images.normal, &images.geometric_normal, &images.albedo,
                                 &images.emission, &images.motion}) {
        r.colours.push_back(raster_test::download_rgba(*image));
    }
    r.depth = images.depth.download<float>();
    return r;
}

struct MapBytes {
    std::vector<glm::vec4> position, normal, flux;
    std::vector<float> depth;
};

MapBytes render_map(const vplkit::stages::SceneBuffers& scene, vplkit::ShadowMap& map) {
    vplkit::Context& ctx = vplkit::test::context();
    vplkit::PassList passes("scene address shadow map");
    vplkit::stages::add_shadow_map_pass(ctx, passes, scene, map);
    passes.run(ctx);
    return {raster_test::download_rgba(map.position), raster_test::download_rgba(map.normal),
            raster_test::download_rgba(map.flux), map.depth.download<float>()};
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

size_t covered(const std::vector<float>& depth) {
    size_t n = 0;
    for (float d : depth) n += d < 1.0f;
    return n;
}

}  // namespace

TEST_CASE("scene address: vertices and indices at offsets in larger buffers raster like the bindings") {
    vplkit::Context& ctx = vplkit::test::context();
    const vplkit::scene::Scene scene = cornell();
    vplkit::GpuScene gpu = vplkit::GpuScene::create(ctx, scene);
    REQUIRE_FALSE(gpu.addressed());  // the binding path: the reference
    const auto view = vplkit::camera_view(scene.camera(), 64, 64);

    // A pose: every vertex moved, so the motion image is read from the previous vertices.
    vplkit::scene::Scene moved = scene;
    for (vplkit::scene::Vertex& v : moved.vertices) v.position += glm::vec3(0.01f, -0.02f, 0.015f);
    gpu.update_vertices(moved);
    REQUIRE(gpu.has_motion());
    const vplkit::stages::SceneBuffers bound = gpu;

    // Odd decoy counts: views at offsets no storage binding could start at (37 x 72 bytes).
    std::vector<vplkit::Buffer> keep;
    vplkit::stages::SceneBuffers addressed = bound;
    addressed.vertices = placed(keep, moved.vertices, decoy_vertex(), 37, 5, "placed vertices");
    addressed.previous_vertices = placed(keep, scene.vertices, decoy_vertex(), 11, 3, "placed previous vertices");
    addressed.indices = placed(keep, scene.indices, 0u, 7, 4, "placed indices");
    addressed.addressed = true;

    const GbufferBytes expected = render_gbuffer(bound, view);
    const GbufferBytes got = render_gbuffer(addressed, view);
    CHECK(covered(expected.depth) > 64 * 64 / 2);  // the comparison means something
    size_t moving = 0;
    for (const glm::vec4& m : expected.colours[5]) moving += m.x != 0.0f || m.y != 0.0f || m.z != 0.0f;
    CHECK(moving > 64 * 64 / 2);
    for (size_t i = 0; i < expected.colours.size(); ++i) {
        CAPTURE(i);
        CHECK(same_bytes(expected.colours[i], got.colours[i]));
    }
    CHECK(same_bytes(expected.depth, got.depth));

    // A point light's cube map: six faces, each a draw of the whole scene.
    vplkit::scene::Light light;
    light.type = vplkit::scene::LightType::point;
    light.name = "point";
    light.position = gpu.bounds().center();
    light.color = {1.0f, 0.9f, 0.8f};
    light.intensity = 5.0f;
    vplkit::ShadowMap map = vplkit::ShadowMap::create(ctx, light, gpu.bounds(), 32);
    const MapBytes map_expected = render_map(bound, map);
    const MapBytes map_got = render_map(addressed, map);
    CHECK(covered(map_expected.depth) > map_expected.depth.size() / 2);
    CHECK(same_bytes(map_expected.position, map_got.position));
    CHECK(same_bytes(map_expected.normal, map_got.normal));
    CHECK(same_bytes(map_expected.flux, map_got.flux));
    CHECK(same_bytes(map_expected.depth, map_got.depth));
}

TEST_CASE("scene address: a scene past a binding's range must be addressed") {
    // A view the size of the range plus one vertex (the buffer behind it is small: the check
    // comes before anything is recorded).
    vplkit::Context& ctx = vplkit::test::context();
    const vplkit::scene::Scene scene = cornell();
    const vplkit::GpuScene gpu = vplkit::GpuScene::create(ctx, scene);
    vplkit::stages::SceneBuffers too_big = gpu;
    too_big.vertices.size = ctx.info().max_storage_buffer_range + sizeof(vplkit::scene::Vertex);
    auto images = vplkit::GbufferImages::create(ctx, 8, 8);
    vplkit::PassList passes("scene address refusal");
    const auto view = vplkit::camera_view(scene.camera(), 8, 8);
    vplkit::test::check_refused_past_range(
        ctx, {"scene vertices"}, [&] { vplkit::stages::add_gbuffer_pass(ctx, passes, too_big, view, images); });
}
