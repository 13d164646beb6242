// An `addressed` BVH (stages/bvh_buffers.hpp) is traversed at the device addresses in the alpha
// buffer's header (bvh.glsl), not through its bindings, which bind_bvh then makes one record
// wide: what a BVH past maxStorageBufferRange takes, tested here without a 4M-triangle scene
// by forcing the path on small ones. Nodes and triangles placed at offsets inside larger buffers
// full of decoy records give the hits of the plain upload's binding path, bit for bit, and the
// header's record counts keep a malformed tree's indices inside its buffers. Alpha-test records
// read at the alpha buffer's own address (past the range, as nodes and triangles) cut out what
// the binding's records cut out.

#include "bvh_test_support.hpp"
#include "vplkit/buffer.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/bvh_gpu_build.hpp"
#include "vplkit/context.hpp"
#include "vplkit/stages/bvh_buffers.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/vec3.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

namespace {

using vplkit::shaders::BvhHit;
using vplkit::shaders::BvhNode;
using vplkit::shaders::BvhRay;
using vplkit::shaders::BvhTriangle;

constexpr VkBufferUsageFlags kAddressed =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

// `records` at byte `offset` of a buffer `before` + `after` records larger, the rest filled with
// `decoy`: a traversal that read the wrong place would meet decoys, not the records.
template <class T>
vplkit::Buffer placed(const std::vector<T>& records, const T& decoy, size_t before, size_t after, const char* name) {
    std::vector<T> contents(before, decoy);
    contents.insert(contents.end(), records.begin(), records.end());
    contents.insert(contents.end(), after, decoy);
    vplkit::Buffer buffer = vplkit::Buffer::create(vplkit::test::context(), contents.size() * sizeof(T), kAddressed,
                                                   vplkit::MemoryUse::device, name);
    buffer.upload(contents);
    return buffer;
}

// A BvhBuffers over views of `nodes` and `triangles` starting `before` records in, `count`
// records long, with the header in a fresh alpha buffer (kept in `alpha`).
vplkit::stages::BvhBuffers views_at(const vplkit::Buffer& nodes, size_t node_count, const vplkit::Buffer& triangles,
                                    size_t triangle_count, size_t before, const vplkit::Bvh& bvh,
                                    vplkit::Buffer& alpha) {
    const vplkit::BufferView node_view{nodes.handle(), before * sizeof(BvhNode), node_count * sizeof(BvhNode), "nodes"};
    const vplkit::BufferView triangle_view{triangles.handle(), before * sizeof(BvhTriangle),
                                           triangle_count * sizeof(BvhTriangle), "triangles"};
    vplkit::Context& ctx = vplkit::test::context();
    const auto header = vplkit::stages::bvh_header(ctx.device(), node_view, triangle_view);
    alpha = vplkit::Buffer::create(ctx, sizeof(header), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vplkit::MemoryUse::device,
                                   "bvh alpha");
    alpha.upload(header.data(), sizeof(header));
    return {node_view, triangle_view, uint32_t(node_count), uint32_t(triangle_count), bvh.scene_scale, alpha,
            false,     true};
}

std::vector<BvhRay> random_rays(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> box(-1.2f, 1.2f);
    std::vector<BvhRay> rays;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 origin(box(rng), box(rng), box(rng));
        // Half unbounded, half short segments (shadow rays that may stop before any triangle).
        rays.push_back(vplkit::bvh_test::make_ray(origin, vplkit::bvh_test::random_direction(rng), 0.0f,
                                                  i % 2 ? 0.5f : std::numeric_limits<float>::infinity()));
    }
    return rays;
}

}  // namespace

TEST_CASE("bvh address: nodes and triangles at offsets inside larger buffers trace like the plain upload") {
    vplkit::Context& ctx = vplkit::test::context();
    const vplkit::bvh_test::Triangles soup = vplkit::bvh_test::random_soup(3000, 11);
    const vplkit::Bvh bvh = vplkit::build_bvh(soup);
    const vplkit::GpuBvh plain = vplkit::upload_bvh(ctx, bvh);
    REQUIRE_FALSE(plain.addressed);  // the binding path: the reference

    // Decoys that would change answers if read: a node whose box holds everything and whose
    // leaf is triangles 0-3, and a triangle across the whole scene with an id no input has.
    BvhNode node_decoy{};
    node_decoy.lo = {-1e3f, -1e3f, -1e3f};
    node_decoy.hi = {1e3f, 1e3f, 1e3f};
    node_decoy.index = 0;
    node_decoy.meta = vplkit::kBvhLeafFlag | 4u;
    BvhTriangle triangle_decoy{};
    triangle_decoy.v0 = {-1e3f, -1e3f, 0.0f};
    triangle_decoy.v1 = {1e3f, -1e3f, 0.0f};
    triangle_decoy.v2 = {0.0f, 1e3f, 0.0f};
    triangle_decoy.id = 999999;
    const size_t before = 37, after = 5;  // odd counts: the views start at unaligned-to-256 offsets
    const vplkit::Buffer nodes = placed(bvh.nodes, node_decoy, before, after, "placed nodes");
    const vplkit::Buffer triangles = placed(bvh.triangles, triangle_decoy, before, after, "placed triangles");
    vplkit::Buffer alpha;
    const vplkit::stages::BvhBuffers offset_bvh =
        views_at(nodes, bvh.nodes.size(), triangles, bvh.triangles.size(), before, bvh, alpha);

    const std::vector<BvhRay> rays = random_rays(4096, 5);
    const std::vector<BvhHit> expected = vplkit::bvh_test::trace_closest(plain, rays);
    const std::vector<BvhHit> hits = vplkit::bvh_test::trace_closest(offset_bvh, rays);
    const std::vector<uint32_t> expected_occlusion = vplkit::bvh_test::trace_occlusion(plain, rays);
    const std::vector<uint32_t> occlusion = vplkit::bvh_test::trace_occlusion(offset_bvh, rays);
    size_t hit_count = 0, occluded = 0, differ = 0;
    for (size_t r = 0; r < rays.size(); ++r) {
        hit_count += expected[r].id != vplkit::kBvhNoHit;
        occluded += expected_occlusion[r] != 0;
        // Bit for bit: the same records, the same traversal.
        const BvhHit& e = expected[r];
        const BvhHit& h = hits[r];
        const bool same = std::memcmp(&e.t, &h.t, sizeof(float)) == 0 && e.id == h.id && e.triangle == h.triangle &&
                          std::memcmp(&e.barycentrics, &h.barycentrics, sizeof(e.barycentrics)) == 0 &&
                          expected_occlusion[r] == occlusion[r];
        differ += !same;
    }
    MESSAGE(hit_count << " of " << rays.size() << " rays hit, " << occluded << " occluded");
    CHECK(hit_count > rays.size() / 4);  // the comparison means something
    CHECK(occluded > rays.size() / 8);
    CHECK(differ == 0);
}

TEST_CASE("bvh address: a malformed tree's indices stay inside its buffers") {
    // A root whose second child and a leaf whose first triangle lie far past the buffers (2^31
    // nodes, 2^30 triangles: tens of GB away): the header's record counts clamp them to the last
    // node and triangle, so the traversal reads records of this BVH (and gives some answer)
    // instead of faulting.
    vplkit::Context& ctx = vplkit::test::context();
    const vplkit::bvh_test::Triangles one = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    vplkit::Bvh bvh = vplkit::build_bvh(one);
    REQUIRE(bvh.nodes.size() == 1);
    BvhNode root = bvh.nodes[0];
    BvhNode leaf = root;
    leaf.index = 1u << 30;
    root.meta = 0;  // interior, split along x
    root.index = 0x7fffffffu;
    bvh.nodes = {root, leaf};
    const vplkit::GpuBvh uploaded = vplkit::upload_bvh(ctx, bvh);
    vplkit::stages::BvhBuffers gpu = uploaded;
    gpu.addressed = true;
    std::vector<BvhRay> rays;
    for (int i = 0; i < 64; ++i) {
        rays.push_back(vplkit::bvh_test::make_ray({0.01f * float(i - 32), 0.0f, 1.0f}, {0.0f, 0.0f, -1.0f}, 0.0f,
                                                  std::numeric_limits<float>::infinity()));
    }
    const std::vector<BvhHit> hits = vplkit::bvh_test::trace_closest(gpu, rays);
    for (const BvhHit& hit : hits) CHECK((hit.id == 0u || hit.id == vplkit::kBvhNoHit));
}

TEST_CASE("bvh address: alpha-test records at the header's address cut out what the binding's do") {
    // Alpha-test records past the range are read at the alpha buffer's address (header words 1,
    // 8-9): forced here on 2000 triangles, three of four with a record: corner alphas (1, 1, 0)
    // (half cut out), (0, 0, 0) (cut out), and a 4 x 4 checker texture (its alpha bytes in the
    // records too). The addressed traversal gives the bound one's hits and occlusion bit for bit.
    vplkit::Context& ctx = vplkit::test::context();
    const vplkit::bvh_test::Triangles soup = vplkit::bvh_test::random_soup(2000, 93, 0.2f);
    vplkit::GpuBvhAlphaRecords alpha;
    alpha.words.assign(vplkit::kBvhHeaderWords, 0u);
    const uint32_t plain = uint32_t(alpha.words.size());
    alpha.words.insert(alpha.words.end(), {std::bit_cast<uint32_t>(0.5f), 0u, 0u, 0u, 0u});
    const uint32_t textured = uint32_t(alpha.words.size());
    alpha.words.insert(alpha.words.end(), {std::bit_cast<uint32_t>(0.5f), 4u, 4u, 0u, 0u});
    alpha.words.back() = uint32_t(alpha.words.size());  // the texture's bytes follow
    for (uint32_t row = 0; row < 4; ++row) alpha.words.push_back(row % 2 ? 0x00ff00ffu : 0xff00ff00u);
    for (uint32_t t = 0; t < 2000; ++t) {
        if (t % 4 == 0) {
            alpha.triangle_records.push_back(0);
            continue;
        }
        alpha.triangle_records.push_back(uint32_t(alpha.words.size()));
        const float uvs[6] = {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f};
        for (float uv : uvs) alpha.words.push_back(std::bit_cast<uint32_t>(uv));
        const float corners[3][3] = {{1, 1, 0}, {0, 0, 0}, {1, 1, 1}};
        for (int k = 0; k < 3; ++k) alpha.words.push_back(std::bit_cast<uint32_t>(corners[t % 4 - 1][k]));
        alpha.words.push_back(t % 4 == 3 ? textured : plain);
    }
    const vplkit::GpuBvhBuild build(ctx, soup, {}, {}, &alpha);
    const vplkit::GpuBvh& gpu = build.bvh();
    REQUIRE(gpu.alpha_tests);
    REQUIRE_FALSE(gpu.addressed);
    const std::vector<uint32_t> header = gpu.alpha.download<uint32_t>(vplkit::kBvhHeaderWords);
    CHECK(header[1] == gpu.alpha.size() / sizeof(uint32_t));  // the records' address is in the header
    vplkit::stages::BvhBuffers addressed = gpu;
    addressed.addressed = true;

    const std::vector<BvhRay> rays = random_rays(4096, 94);
    const std::vector<BvhHit> expected = vplkit::bvh_test::trace_closest(gpu, rays);
    const std::vector<BvhHit> hits = vplkit::bvh_test::trace_closest(addressed, rays);
    const std::vector<uint32_t> expected_occlusion = vplkit::bvh_test::trace_occlusion(gpu, rays);
    const std::vector<uint32_t> occlusion = vplkit::bvh_test::trace_occlusion(addressed, rays);
    size_t masked_hits = 0, differ = 0;
    for (size_t r = 0; r < rays.size(); ++r) {
        const BvhHit& e = expected[r];
        const BvhHit& h = hits[r];
        masked_hits += e.id != vplkit::kBvhNoHit && e.id % 4 != 0;
        differ += !(std::memcmp(&e.t, &h.t, sizeof(float)) == 0 && e.id == h.id && e.triangle == h.triangle &&
                    expected_occlusion[r] == occlusion[r]);
    }
    MESSAGE(masked_hits << " of " << rays.size() << " rays hit a triangle with an alpha record");
    CHECK(masked_hits > rays.size() / 16);  // the records are read
    CHECK(differ == 0);
}
