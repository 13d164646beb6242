// The GPU BVH build with its buffers read and written at their device addresses
// (BvhGpuBuildBuffers::addressed, bvh_build.glsl's kBvhBuildAddressed): what a scene past
// maxStorageBufferRange takes (2.1M triangles on lavapipe), tested here without one by forcing
// the path on small scenes. The addressed build, and its refit, write the bound build's nodes,
// triangles, masked root and statistics, byte for byte.

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

template <class T>
std::vector<T> all_of(const vplkit::Buffer& buffer) {
    return buffer.download<T>(buffer.size() / sizeof(T));
}

bool same_buffers(const GpuBvhBuild& a, const GpuBvhBuild& b) {
    const auto a_nodes = all_of<vplkit::shaders::BvhNode>(a.bvh().nodes);
    const auto b_nodes = all_of<vplkit::shaders::BvhNode>(b.bvh().nodes);
    const auto a_triangles = all_of<vplkit::shaders::BvhTriangle>(a.bvh().triangles);
    const auto b_triangles = all_of<vplkit::shaders::BvhTriangle>(b.bvh().triangles);
    const auto a_alpha = all_of<uint32_t>(a.bvh().alpha);
    const auto b_alpha = all_of<uint32_t>(b.bvh().alpha);
    // Word 0 of the alpha buffer: the masked root the build writes; the rest of the header holds
    // each build's own addresses.
    return a_nodes.size() == b_nodes.size() &&
           std::memcmp(a_nodes.data(), b_nodes.data(), a_nodes.size() * sizeof(a_nodes[0])) == 0 &&
           a_triangles.size() == b_triangles.size() &&
           std::memcmp(a_triangles.data(), b_triangles.data(), a_triangles.size() * sizeof(a_triangles[0])) == 0 &&
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
