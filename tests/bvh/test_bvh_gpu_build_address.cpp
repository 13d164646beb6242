// The GPU BVH build with its buffers read and written at their device addresses
// (BvhGpuBuildBuffers::addressed, bvh_build.glsl's kBvhBuildAddressed): what a scene past
// maxStorageBufferRange takes (2.1M triangles on lavapipe), tested here without one by forcing
// the path on small scenes. The addressed build, and its refit, write the bound build's nodes,
// triangles (their members), masked root and statistics, byte for byte.

#include "bvh_test_support.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu_build.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/vec3.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

namespace {

using vplkit::GpuBvhBuild;
using vplkit::bvh_test::Triangles;

// What a build writes, and only that: its nodes up to node_count (the buffer holds 2n - 1 slots,
// the rest never written) and its triangles' members (a record's last 4 bytes pad it to its
// 48-byte stride, and a struct store does not write them). Both are uninitialised device memory,
// whatever the heap held before (a test case run after another in one process finds them
// differing), so comparing whole buffers flaked; the build itself writes the same bytes.
bool same_triangle(const vplkit::shaders::BvhTriangle& x, const vplkit::shaders::BvhTriangle& y) {
    const auto same = [](const vplkit::shaders::vec3& p, const vplkit::shaders::vec3& q) {
        return std::memcmp(&p, &q, sizeof(p)) == 0;
    };
    return same(x.v0, y.v0) && same(x.v1, y.v1) && same(x.v2, y.v2) && x.id == y.id && x.alpha == y.alpha;
}

bool same_buffers(const GpuBvhBuild& a, const GpuBvhBuild& b) {
    if (a.bvh().node_count != b.bvh().node_count || a.bvh().triangle_count != b.bvh().triangle_count) return false;
    const auto a_nodes = a.bvh().nodes.download<vplkit::shaders::BvhNode>(a.bvh().node_count);
    const auto b_nodes = b.bvh().nodes.download<vplkit::shaders::BvhNode>(b.bvh().node_count);
    const auto a_triangles = a.bvh().triangles.download<vplkit::shaders::BvhTriangle>(a.bvh().triangle_count);
    const auto b_triangles = b.bvh().triangles.download<vplkit::shaders::BvhTriangle>(b.bvh().triangle_count);
    const auto a_alpha = a.bvh().alpha.download<uint32_t>(a.bvh().alpha.size() / sizeof(uint32_t));
    const auto b_alpha = b.bvh().alpha.download<uint32_t>(b.bvh().alpha.size() / sizeof(uint32_t));
    // Word 0 of the alpha buffer: the masked root the build writes; the rest of the header holds
    // each build's own addresses.
    return std::memcmp(a_nodes.data(), b_nodes.data(), a_nodes.size() * sizeof(a_nodes[0])) == 0 &&
           std::equal(a_triangles.begin(), a_triangles.end(), b_triangles.begin(), same_triangle) &&
           a_alpha.size() == b_alpha.size() && a_alpha[0] == b_alpha[0] &&
           std::equal(a_alpha.begin() + vplkit::kBvhHeaderWords, a_alpha.end(),
                      b_alpha.begin() + vplkit::kBvhHeaderWords);
}

void check_same_stats(const GpuBvhBuild& a, const GpuBvhBuild& b) {
    CHECK(a.stats().node_count == b.stats().node_count);
    CHECK(a.stats().leaf_count == b.stats().leaf_count);
    CHECK(a.stats().depth == b.stats().depth);
    CHECK(a.stats().lbvh_depth == b.stats().lbvh_depth);
    CHECK(a.stats().largest_leaf == b.stats().largest_leaf);
    CHECK(a.stats().capped_leaves == b.stats().capped_leaves);
    CHECK(std::bit_cast<uint32_t>(a.bvh().scene_scale) == std::bit_cast<uint32_t>(b.bvh().scene_scale));
}

}  // namespace

TEST_CASE("bvh gpu build address: a forced-addressed build and refit write the bound build's BVH") {
    vplkit::Context& ctx = vplkit::test::context();
    const Triangles soup = vplkit::bvh_test::random_soup(4000, 91, 0.1f);
    GpuBvhBuild bound(ctx, soup);
    GpuBvhBuild addressed(ctx, soup, {}, {}, nullptr, true);
    REQUIRE_FALSE(bound.bvh().addressed);
    CHECK(bound.stats().node_count > 1000);  // the comparison means something
    check_same_stats(bound, addressed);
    CHECK(same_buffers(bound, addressed));

    // A refit (bounds, leaves, levels and write again) after a shear.
    Triangles moved = soup;
    for (glm::vec3& v : moved) v = glm::vec3(v.x + 0.5f * v.y, 1.5f * v.y, v.z - 0.2f);
    bound.refit(moved);
    addressed.refit(moved);
    check_same_stats(bound, addressed);
    CHECK(same_buffers(bound, addressed));
}

TEST_CASE("bvh gpu build address: the split layout's masked root is written on the addressed path too") {
    // Every other triangle with an alpha record (one material, cutoff 0.5, no texture): the
    // masked ones go to a subtree of their own, whose root the build writes into word 0.
    vplkit::Context& ctx = vplkit::test::context();
    const Triangles soup = vplkit::bvh_test::random_soup(1000, 92, 0.1f);
    vplkit::GpuBvhAlphaRecords alpha;
    alpha.words.assign(vplkit::kBvhHeaderWords, 0u);
    const uint32_t material = uint32_t(alpha.words.size());
    alpha.words.insert(alpha.words.end(), {std::bit_cast<uint32_t>(0.5f), 0u, 0u, 0u, 0u});
    for (uint32_t t = 0; t < 1000; ++t) {
        if (t % 2 == 0) {
            alpha.triangle_records.push_back(0);
            continue;
        }
        alpha.triangle_records.push_back(uint32_t(alpha.words.size()));
        alpha.words.insert(alpha.words.end(), 6, 0u);
        for (int k = 0; k < 3; ++k) alpha.words.push_back(std::bit_cast<uint32_t>(1.0f));
        alpha.words.push_back(material);
    }
    const GpuBvhBuild bound(ctx, soup, {}, {}, &alpha);
    const GpuBvhBuild addressed(ctx, soup, {}, {}, &alpha, true);
    CHECK(bound.stats().masked_root != 0u);  // a split tree
    CHECK(addressed.stats().masked_root == bound.stats().masked_root);
    check_same_stats(bound, addressed);
    CHECK(same_buffers(bound, addressed));
}
