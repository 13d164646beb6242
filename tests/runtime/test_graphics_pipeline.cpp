// GraphicsPipeline: a vertex and a fragment shader (generated Module types) drawn with dynamic
// rendering into a colour and a depth target, compared with a CPU rasterization at pixel centres.
// Pixels whose centre lies within 1e-3 pixels of a triangle edge are skipped: which side they
// fall on depends on the rasterizer's fixed-point snapping and tie rules, not on our code.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/graphics_pipeline.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/runtime_test/raster_triangles.hpp"
#include "vplkit/runtime_test/raster_triangles_fs.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace vs = vplkit::runtime_test::raster_triangles;
namespace fs = vplkit::runtime_test::raster_triangles_fs;

namespace {

using Vec4 = std::array<float, 4>;

// Signed distance in pixels of pixel centre (px, py) from each edge of the screen-space
// triangle; all >= 0 (either winding) means inside.
struct Coverage {
    bool inside = false;
    double min_edge_distance = 0.0;
    double depth = 0.0;
};

Coverage cover(const std::array<Vec4, 3>& clip, double px, double py, int width, int height) {
    double x[3], y[3], z[3];
    for (int i = 0; i < 3; ++i) {
        x[i] = (clip[i][0] / clip[i][3] * 0.5 + 0.5) * width;
        y[i] = (clip[i][1] / clip[i][3] * 0.5 + 0.5) * height;
        z[i] = clip[i][2] / clip[i][3];
    }
    const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    double w[3];
    Coverage c;
    c.min_edge_distance = INFINITY;
    for (int i = 0; i < 3; ++i) {
        const int a = (i + 1) % 3, b = (i + 2) % 3;
        const double e = (x[b] - x[a]) * (py - y[a]) - (px - x[a]) * (y[b] - y[a]);
        const double length = std::hypot(x[b] - x[a], y[b] - y[a]);
        w[i] = e / area;
        c.min_edge_distance = std::min(c.min_edge_distance, std::abs(e) / length);
    }
    c.inside = w[0] >= 0 && w[1] >= 0 && w[2] >= 0;
    c.depth = w[0] * z[0] + w[1] * z[1] + w[2] * z[2];
    return c;
}

}  // namespace

TEST_CASE("graphics pipeline: two triangles with a depth test match a CPU rasterization") {
    vplkit::Context& ctx = vplkit::test::context();
    const int width = 48, height = 32;
    // Triangle 0 is nearer (z 0.25) than triangle 1 (z 0.5) where they overlap; opposite windings.
    const std::vector<Vec4> vertices = {
        {-0.8f, -0.7f, 0.25f, 1.0f}, {0.6f, -0.2f, 0.25f, 1.0f}, {-0.3f, 0.9f, 0.25f, 1.0f},
        {-0.9f, 0.3f, 0.5f, 1.0f},   {0.9f, 0.8f, 0.5f, 1.0f},   {0.7f, -0.9f, 0.5f, 1.0f},
    };
    auto vertex_buffer = vplkit::Buffer::create(ctx, vertices.size() * sizeof(Vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                vplkit::MemoryUse::device, "raster test vertices");
    vertex_buffer.upload(vertices);
    auto color = vplkit::Image::create(ctx, width, height, VK_FORMAT_R32G32B32A32_SFLOAT,
                                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "raster test colour");
    auto depth = vplkit::Image::create(ctx, width, height, VK_FORMAT_D32_SFLOAT,
                                       VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "raster test depth");

    vplkit::RasterState state;
    state.color_formats = {VK_FORMAT_R32G32B32A32_SFLOAT};
    state.depth_format = VK_FORMAT_D32_SFLOAT;
    auto pipeline = vplkit::GraphicsPipeline::create<vs::Module, fs::Module>(ctx.device(), ctx.pipeline_cache(), state);
    ctx.set_name(pipeline.handle(), "raster test");

    vplkit::runtime_test::RasterTestPush push{};
    push.colors[0] = {1.0f, 0.0f, 0.0f, 0.0f};
    push.colors[1] = {0.0f, 0.0f, 1.0f, 0.0f};
    vplkit::PassList passes("raster test");
    passes.add("draw",
               {vplkit::Use::read(vertex_buffer, vplkit::Stage::vertex), vplkit::Use::color_attachment(color),
                vplkit::Use::depth_attachment(depth)},
               [&](VkCommandBuffer cmd) {
                   vplkit::begin_rendering(cmd, {{color}, {VkClearColorValue{{0.0f, 0.0f, 0.0f, -1.0f}}}, depth, 1.0f});
                   pipeline.bind(cmd);
                   vs::Bindings bindings;
                   bindings.vertices = vertex_buffer.descriptor();
                   pipeline.push_descriptors<vs::Module, fs::Module>(cmd, bindings, {});
                   pipeline.push_constants(cmd, push);
                   vkCmdDraw(cmd, 6, 1, 0, 0);
                   vplkit::end_rendering(cmd);
               });
    passes.run(ctx);
    auto texels = color.download<Vec4>();
    auto depths = depth.download<float>();

    int compared = 0, covered[2] = {0, 0};
    for (int py = 0; py < height; ++py) {
        for (int px = 0; px < width; ++px) {
            double nearest = 1.0;
            int expected = -1;  // -1: background
            bool near_edge = false;
            for (int t = 0; t < 2; ++t) {
                std::array<Vec4, 3> tri = {vertices[3 * t], vertices[3 * t + 1], vertices[3 * t + 2]};
                Coverage c = cover(tri, px + 0.5, py + 0.5, width, height);
                near_edge |= c.min_edge_distance < 1e-3;
                if (c.inside && c.depth < nearest) {
                    nearest = c.depth;
                    expected = t;
                }
            }
            if (near_edge) continue;
            ++compared;
            const Vec4& got = texels[py * width + px];
            CAPTURE(px);
            CAPTURE(py);
            CHECK(got[3] == float(expected));  // alpha: triangle index, -1 for the clear colour
            if (expected >= 0) {
                ++covered[expected];
                CHECK(got[0] == push.colors[expected].x);
                CHECK(got[2] == push.colors[expected].z);
                CHECK(depths[py * width + px] == doctest::Approx(nearest).epsilon(1e-6));
            } else {
                CHECK(depths[py * width + px] == 1.0f);
            }
        }
    }
    CHECK(compared > width * height * 9 / 10);
    CHECK(covered[0] > 50);  // both triangles visible somewhere
    CHECK(covered[1] > 50);
}

TEST_CASE("graphics pipeline: push constants of the wrong size are refused") {
    vplkit::Context& ctx = vplkit::test::context();
    vplkit::RasterState state;
    state.color_formats = {VK_FORMAT_R32G32B32A32_SFLOAT};
    auto pipeline = vplkit::GraphicsPipeline::create<vs::Module, fs::Module>(ctx.device(), ctx.pipeline_cache(), state);
    uint32_t too_small = 0;
    ctx.one_shot([&](VkCommandBuffer cmd) {
        CHECK_THROWS_WITH_AS(pipeline.push_constants(cmd, too_small), doctest::Contains("pushed 4 bytes"),
                             vplkit::Error);
    });
}
