// The GPU BVH build (stages/bvh_gpu_build.hpp, runtime GpuBvhBuild) against the host build
// (vplkit/bvh.hpp): its structure, and the same answers for many random rays traced through
// both with the same traversal (shaders/bvh/trace_*.comp over vplkit/bvh.glsl).
//
// Tolerances (why): both trees hold the same float triangles and the traversal's triangle test
// is the same float code, so a ray's set of hit triangles does not depend on the tree (boxes
// are padded and only prune); the closest t is the same float min, and occlusion is the same
// answer, exactly. Only which of two triangles at the very same t is reported may differ (a ray
// through a shared edge, overlapping soup triangles): a tie, accepted when the two t agree to
// 1e-5 relative (bvh_test_support.hpp's tolerance) and rare.
//
// The shaders each check covers (the build's passes, shaders/bvh/; the reference is the host
// build and a per-node walk of the result):
//   bvh_build_bounds     the root box and scene scale equal the host's, bit for bit
//   bvh_build_keys       the alpha split case (the masked key bit puts the masked triangles in the
//                        root's second subtree; removing it failed that case)
//   bvh_build_hierarchy  every triangle in exactly one leaf, every triangle inside its leaf's box
//   bvh_build_depths     the reported depth and the capped leaves (the 38-deep LBVH case)
//   bvh_build_leaves     each leaf's triangles are the input's vertices and ids
//   bvh_build_level      every child box inside its parent's (breaking the passes above depth 3
//                        failed all seven build cases), the same hits as the host for every ray
//   bvh_build_write      the depth-first layout the traversal reads, node count and leaf counts

#include "bvh_test_support.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/bvh_gpu_build.hpp"
#include "vplkit/scene.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

namespace {

using vplkit::bvh_is_leaf;
using vplkit::bvh_leaf_triangles;
using vplkit::GpuBvhBuild;
using vplkit::kBvhNoHit;
using vplkit::bvh_test::make_ray;
using vplkit::bvh_test::Triangles;
using vplkit::shaders::BvhHit;
using vplkit::shaders::BvhNode;
using vplkit::shaders::BvhRay;
using vplkit::shaders::BvhTriangle;
using vplkit::shaders::vec3;

std::filesystem::path source_dir() {
    return std::filesystem::path(VPLKIT_SOURCE_DIR);
}

glm::vec3 to_glm(const vec3& v) {
    return {v.x, v.y, v.z};
}

struct Box {
    glm::vec3 lo{1e30f}, hi{-1e30f};
    void grow(glm::vec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
};

Box bounds(const Triangles& triangles) {
    Box box;
    for (const auto& v : triangles) box.grow(v);
    return box;
}

// Half the rays from random points in the (enlarged) scene box in random directions, with
// tmax random or unbounded; half segments between random points on two random triangles
// (tmax 1, the shadow rays of a renderer), so that most rays start among the geometry.
std::vector<BvhRay> random_rays(const Triangles& triangles, uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> fraction(0.0f, 1.0f);
    const Box box = bounds(triangles);
    const glm::vec3 centre = 0.5f * (box.lo + box.hi);
    const glm::vec3 half = 0.6f * (box.hi - box.lo) + glm::vec3(1e-3f);
    const float size = glm::length(box.hi - box.lo);
    const uint32_t triangle_count = uint32_t(triangles.size() / 3);
    auto surface_point = [&]() {
        const uint32_t t = std::min(triangle_count - 1, uint32_t(fraction(rng) * float(triangle_count)));
        float u = fraction(rng), v = fraction(rng);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        return triangles[3 * t] + u * (triangles[3 * t + 1] - triangles[3 * t]) +
               v * (triangles[3 * t + 2] - triangles[3 * t]);
    };
    std::vector<BvhRay> rays;
    for (uint32_t i = 0; i < count; ++i) {
        if (i % 2 == 0) {
            const glm::vec3 origin = centre + half * glm::vec3(2.0f * fraction(rng) - 1.0f, 2.0f * fraction(rng) - 1.0f,
                                                               2.0f * fraction(rng) - 1.0f);
            const glm::vec3 direction = vplkit::bvh_test::random_direction(rng);
            const float tmax = (i % 4 == 0) ? INFINITY : size * fraction(rng);
            rays.push_back(make_ray(origin, direction, 0.0f, tmax));
        } else {
            const glm::vec3 from = surface_point(), to = surface_point();
            // Off both surfaces by a little of the scene size, as offset_ray_origin moves them.
            rays.push_back(make_ray(from, to - from, 1e-4f, 1.0f - 1e-4f));
        }
    }
    return rays;
}

// Every stored triangle in exactly one leaf, each one of the input triangles (by id) with its
// vertices, every child box inside its parent's, every triangle inside its leaf's box, the
// depth-first layout (first child next), depth and leaf sizes within the stated limits.
// `records`: each input triangle's alpha record offset (empty: all 0).
void check_structure(const GpuBvhBuild& build, const Triangles& triangles, uint32_t max_leaf, uint32_t max_depth,
                     const std::vector<uint32_t>& records = {}) {
    const auto& gpu = build.bvh();
    const auto nodes = gpu.nodes.download<BvhNode>(gpu.node_count);
    const auto stored = gpu.triangles.download<BvhTriangle>(gpu.triangle_count);
    REQUIRE(gpu.triangle_count == triangles.size() / 3 - build.stats().degenerate_triangles);
    std::vector<uint32_t> leaf_of(stored.size(), 0), id_seen(triangles.size() / 3, 0);
    size_t outside = 0, wrong_vertices = 0, bad_layout = 0, big_leaves = 0;
    uint32_t deepest = 0, leaves = 0;
    auto inside = [](glm::vec3 p, const BvhNode& n) {
        return p.x >= n.lo.x && p.y >= n.lo.y && p.z >= n.lo.z && p.x <= n.hi.x && p.y <= n.hi.y && p.z <= n.hi.z;
    };
    // Depth-first walk with an explicit stack of (node, depth); also counts the nodes reached.
    std::vector<std::pair<uint32_t, uint32_t>> stack = {{0u, 0u}};
    uint32_t reached = 0;
    while (!stack.empty()) {
        const auto [index, depth] = stack.back();
        stack.pop_back();
        REQUIRE(index < nodes.size());
        ++reached;
        deepest = std::max(deepest, depth);
        const BvhNode& node = nodes[index];
        if (bvh_is_leaf(node)) {
            ++leaves;
            const uint32_t count = bvh_leaf_triangles(node);
            CHECK(count >= 1);
            big_leaves += count > max_leaf ? 1 : 0;
            REQUIRE(uint64_t(node.index) + count <= stored.size());
            for (uint32_t i = node.index; i < node.index + count; ++i) {
                ++leaf_of[i];
                const BvhTriangle& tri = stored[i];
                outside +=
                    !inside(to_glm(tri.v0), node) || !inside(to_glm(tri.v1), node) || !inside(to_glm(tri.v2), node);
                REQUIRE(tri.id < id_seen.size());
                ++id_seen[tri.id];
                wrong_vertices += to_glm(tri.v0) != triangles[3 * tri.id] ||
                                  to_glm(tri.v1) != triangles[3 * tri.id + 1] ||
                                  to_glm(tri.v2) != triangles[3 * tri.id + 2] ||
                                  tri.alpha != (records.empty() ? 0u : records[tri.id]);
            }
            continue;
        }
        CHECK(node.meta <= 2u);
        const uint32_t first = index + 1, second = node.index;
        bad_layout += !(second > first && second < nodes.size());
        REQUIRE(second < nodes.size());
        for (uint32_t child : {first, second}) {
            outside += !inside(to_glm(nodes[child].lo), node) || !inside(to_glm(nodes[child].hi), node);
        }
        stack.push_back({second, depth + 1});
        stack.push_back({first, depth + 1});
    }
    CHECK(reached == nodes.size());  // node_count nodes, every one in the tree
    CHECK(leaves == build.stats().leaf_count);
    CHECK(deepest == build.stats().depth);
    CHECK(deepest <= max_depth);
    CHECK(std::count(leaf_of.begin(), leaf_of.end(), 1u) == long(leaf_of.size()));
    CHECK(outside == 0);
    CHECK(wrong_vertices == 0);
    CHECK(bad_layout == 0);
    CHECK(big_leaves == build.stats().capped_leaves);
    size_t ids_once = 0;
    for (uint32_t seen : id_seen) ids_once += seen == 1 ? 1 : 0;
    CHECK(ids_once == stored.size());
    // The root box is the host's: the same padded bounds give the same scene scale.
    const vplkit::Bvh host = vplkit::build_bvh(triangles);
    CHECK(nodes[0].lo.x == host.nodes[0].lo.x);
    CHECK(nodes[0].hi.z == host.nodes[0].hi.z);
    CHECK(gpu.scene_scale == host.scene_scale);
}

struct Comparison {
    size_t hits = 0, ties = 0, failures = 0;
};

// Traces `rays` through `host` and `gpu`; see the top of the file.
Comparison compare_traces(const vplkit::GpuBvh& host, const vplkit::GpuBvh& gpu, const std::vector<BvhRay>& rays) {
    const auto host_hits = vplkit::bvh_test::trace_closest(host, rays);
    const auto gpu_hits = vplkit::bvh_test::trace_closest(gpu, rays);
    const auto host_occluded = vplkit::bvh_test::trace_occlusion(host, rays);
    const auto gpu_occluded = vplkit::bvh_test::trace_occlusion(gpu, rays);
    Comparison c;
    for (size_t r = 0; r < rays.size(); ++r) {
        const BvhHit& h = host_hits[r];
        const BvhHit& g = gpu_hits[r];
        const double dlen = glm::length(to_glm(rays[r].direction));
        const double tolerance = vplkit::bvh_test::kRelativeTolerance * std::max(double(h.t), host.scene_scale / dlen);
        bool ok = (h.id == kBvhNoHit) == (g.id == kBvhNoHit) && std::fabs(double(h.t) - double(g.t)) <= tolerance;
        if (ok && h.id != g.id) {
            ++c.ties;
        }
        ok = ok && host_occluded[r] == gpu_occluded[r];
        c.hits += h.id != kBvhNoHit ? 1 : 0;
        if (!ok && ++c.failures <= 5) {
            MESSAGE("ray " << r << ": host id " << h.id << " t " << h.t << " occluded " << host_occluded[r]
                           << "; gpu id " << g.id << " t " << g.t << " occluded " << gpu_occluded[r]);
        }
    }
    MESSAGE(rays.size() << " rays, " << c.hits << " hits, " << c.ties << " ties, " << c.failures << " failures");
    CHECK(c.failures == 0);
    CHECK(double(c.ties) <= 0.01 * double(c.hits));
    return c;
}

// Traces `rays` through the host build of `triangles` and through `gpu`.
Comparison compare_with_host(const Triangles& triangles, const vplkit::GpuBvh& gpu, const std::vector<BvhRay>& rays) {
    const vplkit::GpuBvh host = vplkit::upload_bvh(vplkit::test::context(), vplkit::build_bvh(triangles));
    return compare_traces(host, gpu, rays);
}

void check_scene(const Triangles& triangles, uint32_t ray_count, uint32_t seed) {
    const GpuBvhBuild build(vplkit::test::context(), triangles);
    const auto& s = build.stats();
    MESSAGE((triangles.size() / 3) << " triangles: " << s.node_count << " nodes, " << s.leaf_count << " leaves, depth "
                                   << s.depth << " (LBVH " << s.lbvh_depth << "), " << s.capped_leaves
                                   << " capped leaves, largest " << s.largest_leaf);
    check_structure(build, triangles, vplkit::kBvhMaxLeafTriangles, vplkit::kBvhMaxDepth);
    const auto c = compare_with_host(triangles, build.bvh(), random_rays(triangles, ray_count, seed));
    CHECK(c.hits > ray_count / 4);  // the rays do meet the scene
}

Triangles scene_triangles(const std::filesystem::path& path) {
    return vplkit::scene::triangle_positions(vplkit::scene::load_gltf(path));
}

}  // namespace

TEST_CASE("bvh gpu build: a random triangle soup - structure, and the host BVH's hits and occlusion") {
    check_scene(vplkit::bvh_test::random_soup(20000, 71, 0.05f), 40000, 72);
}

TEST_CASE("bvh gpu build: the in-repo Cornell box - structure, and the host BVH's hits and occlusion") {
    check_scene(scene_triangles(source_dir() / "scenes" / "cornell_emissive" / "cornell_emissive.gltf"), 20000, 73);
}

TEST_CASE("bvh gpu build: the Breakfast Room - structure, and the host BVH's hits and occlusion") {
    const auto path = source_dir() / ".." / "shared" / "scenes" / "BreakfastRoom" / "BreakfastRoom.gltf";
    if (!std::filesystem::exists(path)) {
        MESSAGE("skipped: " << path.string() << " is not there");
        return;
    }
    check_scene(scene_triangles(path), 40000, 74);
}

TEST_CASE("bvh gpu build: leaves of one triangle, and leaves capped at a small max_depth") {
    const Triangles soup = vplkit::bvh_test::random_soup(3000, 75, 0.1f);
    const auto rays = random_rays(soup, 10000, 76);
    SUBCASE("one triangle a leaf") {
        vplkit::stages::BvhGpuBuildOptions options;
        options.max_leaf_triangles = 1;
        const GpuBvhBuild build(vplkit::test::context(), soup, {}, options);
        CHECK(build.stats().node_count == 2 * 3000 - 1);
        check_structure(build, soup, 1, vplkit::kBvhMaxDepth);
        compare_with_host(soup, build.bvh(), rays);
    }
    SUBCASE("max_depth 6: leaves at depth 6 take their whole subtree") {
        vplkit::stages::BvhGpuBuildOptions options;
        options.max_depth = 6;
        const GpuBvhBuild build(vplkit::test::context(), soup, {}, options);
        CHECK(build.stats().depth == 6);
        CHECK(build.stats().capped_leaves > 0);
        CHECK(build.stats().largest_leaf > vplkit::kBvhMaxLeafTriangles);
        check_structure(build, soup, vplkit::kBvhMaxLeafTriangles, 6);
        compare_with_host(soup, build.bvh(), rays);
    }
}

TEST_CASE("bvh gpu build: an LBVH deeper than the traversal's stack is capped at kBvhMaxDepth and traces right") {
    // Triangles centred on the Morton grid's cells (the centroid box is [0, 1023]^3): one at
    // each cell whose code has a single bit set, so that the LBVH is a chain of one level per
    // code bit (30), and 200 around cell 0, whose equal codes add 8 levels of positions below.
    Triangles triangles;
    auto add = [&](glm::vec3 p, float h) {
        triangles.push_back(p + glm::vec3(-h, -h, -h));
        triangles.push_back(p + glm::vec3(h, h, -h));
        triangles.push_back(p + glm::vec3(h, -h, h));
    };
    add({1023, 1023, 1023}, 0.25f);
    for (int bit = 0; bit < 30; ++bit) {
        glm::vec3 p(0.0f);
        p[2 - bit % 3] = float(1 << (bit / 3));
        add(p, 0.25f);
    }
    // Nested, parallel (not coplanar): no two at the same t.
    for (int i = 0; i < 200; ++i) add({0, 0, 0}, 0.25f * float(i + 1) / 200.0f);
    const GpuBvhBuild build(vplkit::test::context(), triangles);
    const auto& s = build.stats();
    MESSAGE("LBVH depth " << s.lbvh_depth << ", depth " << s.depth << ", " << s.capped_leaves
                          << " capped leaves, largest " << s.largest_leaf);
    CHECK(s.lbvh_depth > vplkit::kBvhMaxDepth);
    CHECK(s.depth == vplkit::kBvhMaxDepth);
    CHECK(s.capped_leaves > 0);
    check_structure(build, triangles, vplkit::kBvhMaxLeafTriangles, vplkit::kBvhMaxDepth);
    // Rays through the cluster at cell 0, and the random ones.
    auto rays = random_rays(triangles, 4000, 77);
    std::mt19937 rng(78);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (int i = 0; i < 6000; ++i) {
        const glm::vec3 from = 4.0f * glm::vec3(unit(rng), unit(rng), unit(rng));
        const glm::vec3 to = 0.2f * glm::vec3(unit(rng), unit(rng), unit(rng));
        rays.push_back(make_ray(from, to - from, 0.0f, INFINITY));
    }
    const auto c = compare_with_host(triangles, build.bvh(), rays);
    CHECK(c.hits > 3000);
}

TEST_CASE("bvh gpu build: a refit after moving the vertices gives the hits of a rebuild") {
    const Triangles soup = vplkit::bvh_test::random_soup(5000, 78, 0.1f);
    GpuBvhBuild build(vplkit::test::context(), soup);
    // A non-rigid motion: every triangle moves by its own offset, the whole soup is sheared.
    Triangles moved = soup;
    std::mt19937 rng(79);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (size_t t = 0; t < moved.size() / 3; ++t) {
        const glm::vec3 offset = 0.3f * glm::vec3(unit(rng), unit(rng), unit(rng));
        for (int k = 0; k < 3; ++k) {
            glm::vec3& v = moved[3 * t + k];
            v = glm::vec3(v.x + 0.5f * v.y, 1.5f * v.y, v.z) + offset;
        }
    }
    const uint32_t nodes_before = build.stats().node_count;
    build.refit(moved);
    CHECK(build.bvh().node_count == nodes_before);
    check_structure(build, moved, vplkit::kBvhMaxLeafTriangles, vplkit::kBvhMaxDepth);
    compare_with_host(moved, build.bvh(), random_rays(moved, 20000, 80));
}

TEST_CASE("bvh gpu build: alpha-tested triangles in a subtree of their own - the split layout and the host's hits") {
    // Every fourth triangle opaque (no record); the others with alpha records (bvh.glsl) of one
    // material, cutoff 0.5, no texture, corner alphas: (1, 1, 0) half cut out, (0, 0, 0) cut out,
    // (1, 1, 1) tested but solid.
    const Triangles soup = vplkit::bvh_test::random_soup(2000, 83, 0.1f);
    vplkit::GpuBvhAlphaRecords alpha;
    // The header's words, then the material record.
    alpha.words.assign(vplkit::kBvhHeaderWords, 0u);
    const uint32_t material = uint32_t(alpha.words.size());
    alpha.words.insert(alpha.words.end(), {std::bit_cast<uint32_t>(0.5f), 0u, 0u, 0u, 0u});
    std::vector<uint8_t> masked;
    for (uint32_t t = 0; t < 2000; ++t) {
        if (t % 4 == 0) {
            alpha.triangle_records.push_back(0);
            masked.push_back(0);
            continue;
        }
        const float a[3][3] = {{1, 1, 0}, {0, 0, 0}, {1, 1, 1}};
        const float* corner = a[t % 4 - 1];
        alpha.triangle_records.push_back(uint32_t(alpha.words.size()));
        masked.push_back(1);
        alpha.words.insert(alpha.words.end(), 6, 0u);  // UVs: no texture
        for (int k = 0; k < 3; ++k) alpha.words.push_back(std::bit_cast<uint32_t>(corner[k]));
        alpha.words.push_back(material);
    }
    const GpuBvhBuild build(vplkit::test::context(), soup, {}, {}, &alpha);
    const auto& gpu = build.bvh();
    CHECK(gpu.alpha_tests);
    REQUIRE(build.stats().masked_root != 0);
    const auto nodes = gpu.nodes.download<BvhNode>(gpu.node_count);
    CHECK(nodes[0].index == build.stats().masked_root);
    CHECK(gpu.alpha.download<uint32_t>(1)[0] == build.stats().masked_root);
    // The opaque subtree at node 1 holds exactly the triangles without a record, first.
    const auto stored = gpu.triangles.download<BvhTriangle>(gpu.triangle_count);
    size_t misplaced = 0;
    for (uint32_t i = 0; i < stored.size(); ++i) misplaced += (i < 500) != (stored[i].alpha == 0);
    CHECK(misplaced == 0);
    check_structure(build, soup, vplkit::kBvhMaxLeafTriangles, vplkit::kBvhMaxDepth, alpha.triangle_records);

    // The host's split BVH with the same records.
    vplkit::Bvh host_bvh = vplkit::build_bvh_split(soup, masked);
    REQUIRE(host_bvh.masked_root != 0);
    for (auto& tri : host_bvh.triangles) tri.alpha = alpha.triangle_records[tri.id];
    host_bvh.alpha = alpha.words;
    host_bvh.alpha[0] = host_bvh.masked_root;
    const vplkit::GpuBvh host = vplkit::upload_bvh(vplkit::test::context(), host_bvh);
    const auto rays = random_rays(soup, 20000, 84);
    const auto c = compare_traces(host, gpu, rays);
    CHECK(c.hits > 1000);
    // The alpha test ran: nearest hits on every kind but the cut-out one.
    uint32_t per_kind[4] = {};
    for (const auto& hit : vplkit::bvh_test::trace_closest(gpu, rays)) {
        if (hit.id != kBvhNoHit) ++per_kind[hit.id % 4];
    }
    CHECK(per_kind[0] > 200);
    CHECK(per_kind[1] > 100);
    CHECK(per_kind[2] == 0);
    CHECK(per_kind[3] > 200);
}

TEST_CASE("bvh gpu build: degenerate triangles are left out and bad input refused as the host refuses it") {
    Triangles triangles = vplkit::bvh_test::random_soup(100, 81);
    triangles.push_back({0, 0, 0});
    triangles.push_back({1, 1, 1});
    triangles.push_back({2, 2, 2});  // collinear: zero area
    const GpuBvhBuild build(vplkit::test::context(), triangles);
    CHECK(build.stats().degenerate_triangles == 1);
    CHECK(build.bvh().triangle_count == 100);
    check_structure(build, triangles, vplkit::kBvhMaxLeafTriangles, vplkit::kBvhMaxDepth);

    const GpuBvhBuild empty(vplkit::test::context(), Triangles{});
    CHECK(empty.bvh().node_count == 1);
    CHECK(empty.bvh().triangle_count == 0);

    Triangles bad = triangles;
    bad[7].y = NAN;
    CHECK_THROWS_WITH(GpuBvhBuild(vplkit::test::context(), bad),
                      doctest::Contains("triangle 2 has a non-finite vertex"));
    CHECK_THROWS_WITH(GpuBvhBuild(vplkit::test::context(), Triangles(4)), doctest::Contains("whole number"));
}
