// Alpha-tested visibility in the BVH traversal (bvh_alpha_test.glsl's bvh_alpha_passes, records from
// add_alpha_tests): a ray through a MASK material's cut-out passes, elsewhere it is blocked,
// as the G-buffer shows the surface; BLEND is MASK at 0.5; OPAQUE ignores alpha.
//
// Expectation: feature_files' masked_quad (alpha 0, 1, 0, 1, NEAREST filtering), rays straight
// down through the quad at the centres of its 4 texels and either side of a texel border: the
// texel a ray reads is known exactly, so the answer is exact (no tolerance).

#include "feature_files.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/bvh_alpha.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>

#include <vector>

namespace {

// Occlusion of vertical rays through the quad at y = 0.5 and each of `xs` (by default the
// centres of the 4 texels).
std::vector<uint32_t> occlusion(const scene_test::GltfBuilder& b, vplkit::AlphaTestStats* stats = nullptr,
                                const std::vector<float>& xs = {0.125f, 0.375f, 0.625f, 0.875f}) {
    scene_test::TempDir dir("alpha");
    const auto scene = vplkit::scene::load_gltf(b.write(dir.path(), "masked", true));
    vplkit::Bvh bvh = vplkit::build_bvh(vplkit::scene::triangle_positions(scene));
    const auto s = vplkit::add_alpha_tests(bvh, scene);
    if (stats) *stats = s;
    auto& ctx = vplkit::test::context();
    const auto gpu = vplkit::upload_bvh(ctx, bvh);
    std::vector<vplkit::shaders::BvhRay> rays;
    for (float x : xs) {
        vplkit::shaders::BvhRay ray{};
        ray.origin = {x, 0.5f, 1.0f};
        ray.direction = {0.0f, 0.0f, -1.0f};
        ray.tmin = 0.0f;
        ray.tmax = 2.0f;
        rays.push_back(ray);
    }
    auto ray_buffer = vplkit::Buffer::create(ctx, rays.size() * sizeof(rays[0]), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                             vplkit::MemoryUse::device, "rays");
    auto result = vplkit::Buffer::create(ctx, rays.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vplkit::MemoryUse::device, "occlusion");
    ray_buffer.upload(rays);
    vplkit::PassList passes("alpha visibility test");
    vplkit::add_trace_rays_pass(ctx, passes, gpu, ray_buffer, result, uint32_t(rays.size()),
                                vplkit::TraceMode::occlusion);
    passes.run(ctx);
    return result.download<uint32_t>(rays.size());
}

}  // namespace

TEST_CASE("gltf: a masked quad lets a shadow ray through its cut-out and blocks it elsewhere") {
    vplkit::AlphaTestStats stats;
    CHECK(occlusion(gltf_features::masked_quad("MASK"), &stats) == std::vector<uint32_t>{0, 1, 0, 1});
    CHECK(stats.tested_triangles == 2);
    CHECK(stats.texture_bytes == 4);
    // BLEND is drawn where alpha >= 0.5: the same cut-out.
    CHECK(occlusion(gltf_features::masked_quad("BLEND")) == std::vector<uint32_t>{0, 1, 0, 1});
    // OPAQUE ignores alpha: every ray is blocked, and no triangle pays for a test.
    CHECK(occlusion(gltf_features::masked_quad("OPAQUE"), &stats) == std::vector<uint32_t>{1, 1, 1, 1});
    CHECK(stats.tested_triangles == 0);
}

TEST_CASE("gltf: a factor-only alpha below the cutoff lets every ray through, above it blocks every ray") {
    vplkit::AlphaTestStats stats;
    CHECK(occlusion(gltf_features::masked_quad("MASK", 0.4f, false), &stats) == std::vector<uint32_t>{0, 0, 0, 0});
    CHECK(stats.tested_triangles == 2);
    // At or above the cutoff everywhere: opaque, no record (no cost).
    CHECK(occlusion(gltf_features::masked_quad("MASK", 0.6f, false), &stats) == std::vector<uint32_t>{1, 1, 1, 1});
    CHECK(stats.tested_triangles == 0);
    // The texture's alpha times a factor of 0.4: nothing reaches the cutoff.
    CHECK(occlusion(gltf_features::masked_quad("MASK", 0.4f, true)) == std::vector<uint32_t>{0, 0, 0, 0});
}

TEST_CASE("gltf: rays read the mask through the texture's KHR_texture_transform") {
    // Offset 0.25 along u: the rays at x = 0.125, 0.375, 0.625, 0.875 read texels 1, 2, 3, 3 (clamped).
    CHECK(occlusion(gltf_features::masked_quad("MASK", 1.0f, true, 0.25f)) == std::vector<uint32_t>{1, 0, 1, 1});
}

TEST_CASE("gltf: rays read a NEAREST-filtered mask texel by texel, as the G-buffer draws it") {
    // Factor alpha 0.8 x texels 0, 1, 0, 1. At x = 0.27 (texel 1, 0.08 texel past the border)
    // nearest gives 0.8 (blocked, as the G-buffer draws it); bilinear would give 0.8 x 0.58 < 0.5.
    // At x = 0.23 (texel 0) both give less than 0.5: the ray passes.
    CHECK(occlusion(gltf_features::masked_quad("MASK", 0.8f, true), nullptr, {0.23f, 0.27f}) ==
          std::vector<uint32_t>{0, 1});
}
