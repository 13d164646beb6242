// The G-buffer pass (shaders/raster/gbuffer_raster.vert + gbuffer_shade.frag) on lavapipe against
// a CPU rasterization at pixel centres (tests/reference/raster_reference.cpp), and a sanity check
// on the in-repo Cornell box.
//
// Pixels are skipped where the GPU's answer is not determined by our code: the centre within
// 1e-3 pixels of a triangle edge (fixed-point snapping and tie rules), or a texture coordinate
// within 1e-2 texels of a texel border (float interpolation of uv). Tolerances per field:
//   coverage, triangle (via albedo)  exact
//   position     1e-4 x scale (scene ~3 x scale units; float interpolation at 64x64)
//   normals      1e-4 (unit vectors: float normalization and interpolation)
//   roughness, metallic  1e-5 (RGBA32F; UNORM texels are exact in float)
//   albedo, emission     1e-3 relative (RGBA16F: 11-bit mantissa, ~5e-4 relative) plus
//                        3e-3 x the material's factor: lavapipe decodes sRGB texels with an
//                        approximation that differs from the exact IEC 61966-2-1 curve by up to
//                        1.5e-3 (measured); a wrong texel or a missing sRGB decode is off by >0.05
//   depth        1e-6 (D32, depth interpolated linearly on screen)

#include "raster_reference.hpp"
#include "raster_test_scenes.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gpu_scene.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/camera_view.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <vector>

namespace {

using vplkit::reference::GbufferTexel;

struct GbufferRead {
    std::vector<glm::vec4> position, normal, geometric_normal, albedo, emission;
    std::vector<float> depth;
};

GbufferRead render(vplkit::Context& ctx, const vplkit::scene::Scene& scene, const vplkit::stages::CameraView& view,
                   uint32_t width, uint32_t height) {
    auto gpu = vplkit::GpuScene::create(ctx, scene);
    auto images = vplkit::GbufferImages::create(ctx, width, height);
    vplkit::PassList passes("gbuffer test");
    vplkit::stages::add_gbuffer_pass(ctx, passes, gpu, view, images);
    passes.run(ctx);
    GbufferRead r;
    r.position = raster_test::download_rgba(images.position);
    r.normal = raster_test::download_rgba(images.normal);
    r.geometric_normal = raster_test::download_rgba(images.geometric_normal);
    r.albedo = raster_test::download_rgba(images.albedo);
    r.emission = raster_test::download_rgba(images.emission);
    r.depth = images.depth.download<float>();
    return r;
}

void check_close(glm::vec3 got, glm::dvec3 expected, double tolerance, const char* what) {
    const double error = glm::length(glm::dvec3(got) - expected);
    CAPTURE(what);
    CAPTURE(got.x);
    CAPTURE(got.y);
    CAPTURE(got.z);
    CAPTURE(expected.x);
    CAPTURE(expected.y);
    CAPTURE(expected.z);
    CHECK(error <= tolerance);
}

void check_colour(glm::vec3 got, glm::dvec3 expected, glm::vec3 factor, const char* what) {
    for (int c = 0; c < 3; ++c) {
        CAPTURE(what);
        CAPTURE(c);
        CAPTURE(got[c]);
        CAPTURE(expected[c]);
        CHECK(std::abs(got[c] - expected[c]) <= 1e-3 * std::abs(expected[c]) + 3e-3 * factor[c] + 1e-6);
    }
}

}  // namespace

// At scale 1, 1e-3 and 1e4 (positions, camera and planes scaled alike; position tolerance scaled).
TEST_CASE("gbuffer: a small scene matches a CPU rasterization at pixel centres") {
    vplkit::Context& ctx = vplkit::test::context();
    for (float scale : {1.0f, 1e-3f, 1e4f}) {
        CAPTURE(scale);
        const vplkit::scene::Scene scene = raster_test::gbuffer_scene(scale);
        constexpr uint32_t width = 64, height = 64;
        vplkit::scene::Camera camera = vplkit::scene::look_at({0.0f, 0.0f, 3.0f * scale}, {0.0f, 0.0f, 0.0f},
                                                              {0.0f, 1.0f, 0.0f}, glm::radians(60.0f));
        camera.znear = 0.1f * scale;
        camera.zfar = 10.0f * scale;
        const auto view = vplkit::camera_view(camera, width, height);
        const GbufferRead got = render(ctx, scene, view, width, height);
        const auto expected = vplkit::reference::rasterize_gbuffer(scene, glm::dmat4(view.view_projection),
                                                                   glm::dvec3(view.position), width, height);

        int compared = 0, background = 0;
        std::array<int, 5> per_material{};
        for (uint32_t py = 0; py < height; ++py) {
            for (uint32_t px = 0; px < width; ++px) {
                const size_t i = size_t(py) * width + px;
                const GbufferTexel& e = expected[i];
                if (e.ambiguous) continue;
                ++compared;
                CAPTURE(px);
                CAPTURE(py);
                REQUIRE(got.position[i].w == (e.covered ? 1.0f : 0.0f));
                if (!e.covered) {
                    ++background;
                    CHECK(got.depth[i] == 1.0f);
                    CHECK(got.albedo[i] == glm::vec4(0.0f));
                    CHECK(got.normal[i] == glm::vec4(0.0f));
                    continue;
                }
                ++per_material[scene.triangle_materials[size_t(e.triangle)]];
                CAPTURE(e.triangle);
                check_close(glm::vec3(got.position[i]), e.position, 1e-4 * scale, "position");
                check_close(glm::vec3(got.normal[i]), e.normal, 1e-4, "normal");
                check_close(glm::vec3(got.geometric_normal[i]), e.geometric_normal, 1e-4, "geometric normal");
                CHECK(std::abs(got.normal[i].w - e.roughness) <= 1e-5);
                CHECK(std::abs(got.geometric_normal[i].w - e.metallic) <= 1e-5);
                const vplkit::scene::Material& material = scene.materials[scene.triangle_materials[size_t(e.triangle)]];
                check_colour(glm::vec3(got.albedo[i]), e.albedo, glm::vec3(material.base_color_factor), "albedo");
                CHECK(got.albedo[i].w == 1.0f);
                check_colour(glm::vec3(got.emission[i]), e.emission, material.emission(), "emission");
                CHECK(got.emission[i].w == 0.0f);
                CHECK(std::abs(got.depth[i] - e.depth) <= 1e-6);
            }
        }
        CHECK(compared > int(width * height) * 8 / 10);
        CHECK(background > 50);
        for (int m = 0; m < 5; ++m) {
            CAPTURE(m);
            CHECK(per_material[m] > 20);  // every material is seen somewhere
        }
    }
}

TEST_CASE("gbuffer: the in-repo Cornell box gives a sane G-buffer") {
    vplkit::Context& ctx = vplkit::test::context();
    const auto path = std::filesystem::path(VPLKIT_SOURCE_DIR) / "scenes/cornell_point/cornell_point.gltf";
    const vplkit::scene::Scene scene = vplkit::scene::load_gltf(path);
    constexpr uint32_t width = 64, height = 48;
    const auto view = vplkit::camera_view(scene.camera(), width, height);
    const GbufferRead got = render(ctx, scene, view, width, height);

    int covered = 0;
    for (size_t i = 0; i < got.depth.size(); ++i) {
        CAPTURE(i);
        const glm::vec4 p = got.position[i];
        if (p.w == 0.0f) {
            CHECK(got.depth[i] == 1.0f);
            continue;
        }
        REQUIRE(p.w == 1.0f);
        ++covered;
        for (const glm::vec4* v :
             {&got.position[i], &got.normal[i], &got.geometric_normal[i], &got.albedo[i], &got.emission[i]}) {
            CHECK((std::isfinite(v->x) && std::isfinite(v->y) && std::isfinite(v->z) && std::isfinite(v->w)));
        }
        CHECK(std::abs(glm::length(glm::vec3(got.normal[i])) - 1.0f) < 1e-4f);
        CHECK(std::abs(glm::length(glm::vec3(got.geometric_normal[i])) - 1.0f) < 1e-4f);
        // Both normals on the camera's side.
        const glm::vec3 to_eye = view.position - glm::vec3(p);
        CHECK(glm::dot(glm::vec3(got.geometric_normal[i]), to_eye) > 0.0f);
        CHECK(glm::dot(glm::vec3(got.normal[i]), glm::vec3(got.geometric_normal[i])) > 0.0f);
        // Inside the scene's bounds (loosely: float interpolation).
        const glm::vec3 slack = 1e-3f * (scene.bounds.extent() + 1.0f);
        CHECK(glm::all(glm::greaterThanEqual(glm::vec3(p), scene.bounds.min - slack)));
        CHECK(glm::all(glm::lessThanEqual(glm::vec3(p), scene.bounds.max + slack)));
        CHECK(got.depth[i] > 0.0f);
        CHECK(got.depth[i] < 1.0f);
        for (int c = 0; c < 3; ++c) {
            CHECK(got.albedo[i][c] >= 0.0f);
            CHECK(got.albedo[i][c] <= 1.0f);
        }
    }
    // The box fills most of the view from the file's camera.
    CHECK(covered > int(width * height) / 2);
}
