// The host-side BVH build (runtime/src/bvh/build.cpp): structure invariants the traversal relies
// on, the depth cap, SAH quality, and the refusal of bad input. No GPU involved.

#include "bvh_test_support.hpp"
#include "vplkit/bvh.hpp"
#include "vplkit/error.hpp"

#include <doctest/doctest.h>
#include <glm/vec3.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using vplkit::build_bvh;
using vplkit::Bvh;
using vplkit::bvh_is_leaf;
using vplkit::bvh_leaf_triangles;
using vplkit::BvhBuildOptions;
using vplkit::bvh_test::Triangles;
using vplkit::shaders::BvhNode;
using vplkit::shaders::vec3;

bool inside(const vec3& p, const BvhNode& node) {
    return p.x >= node.lo.x && p.y >= node.lo.y && p.z >= node.lo.z && p.x <= node.hi.x && p.y <= node.hi.y &&
           p.z <= node.hi.z;
}

bool contains(const BvhNode& outer, const BvhNode& inner) {
    return inside(inner.lo, outer) && inside(inner.hi, outer);
}

bool same(const vec3& a, const glm::vec3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

struct Walk {
    uint32_t nodes_seen = 0;
    uint32_t leaves = 0;
    uint32_t max_depth = 0;
    std::vector<uint32_t> triangle_leaf_count;  // leaves that reference each stored triangle
    size_t failures = 0;
};

void walk(const Bvh& bvh, uint32_t index, uint32_t depth, Walk& w) {
    ++w.nodes_seen;
    w.max_depth = std::max(w.max_depth, depth);
    REQUIRE(index < bvh.nodes.size());
    const BvhNode& node = bvh.nodes[index];
    if (bvh_is_leaf(node)) {
        ++w.leaves;
        const uint32_t count = bvh_leaf_triangles(node);
        CHECK(count >= 1);
        CHECK(count <= vplkit::kBvhMaxLeafTriangles);
        REQUIRE(uint64_t(node.index) + count <= bvh.triangles.size());
        for (uint32_t i = node.index; i < node.index + count; ++i) {
            ++w.triangle_leaf_count[i];
            const auto& tri = bvh.triangles[i];
            if (!inside(tri.v0, node) || !inside(tri.v1, node) || !inside(tri.v2, node)) {
                ++w.failures;
            }
        }
        return;
    }
    CHECK(node.meta <= 2u);  // split axis
    const uint32_t first = index + 1;
    const uint32_t second = node.index;
    // Depth-first with the first child next to its parent: the second child comes after the
    // whole first subtree.
    REQUIRE(second > first);
    REQUIRE(second < bvh.nodes.size());
    if (!contains(node, bvh.nodes[first]) || !contains(node, bvh.nodes[second])) {
        ++w.failures;
    }
    const uint32_t before = w.nodes_seen;
    walk(bvh, first, depth + 1, w);
    CHECK(second == first + (w.nodes_seen - before));  // the first subtree fills the gap exactly
    walk(bvh, second, depth + 1, w);
}

// Every invariant the traversal depends on; `vertices` are the build's input (default ids).
void check_structure(const Bvh& bvh, const Triangles& vertices, uint32_t max_depth = vplkit::kBvhMaxDepth) {
    REQUIRE(!bvh.nodes.empty());
    Walk w;
    w.triangle_leaf_count.assign(bvh.triangles.size(), 0);
    walk(bvh, 0, 0, w);
    CHECK(w.failures == 0);
    CHECK(w.nodes_seen == bvh.nodes.size());  // every node reachable exactly once
    CHECK(w.leaves == bvh.leaf_count);
    CHECK(bvh.nodes.size() == 2 * size_t(bvh.leaf_count) - 1);
    CHECK(w.max_depth == bvh.depth);
    CHECK(bvh.depth <= max_depth);
    for (uint32_t c : w.triangle_leaf_count) {
        REQUIRE(c == 1);  // in exactly one leaf
    }
    // Each non-degenerate input triangle is stored exactly once, unchanged, under its index.
    std::vector<uint32_t> stored(vertices.size() / 3, 0);
    for (const auto& tri : bvh.triangles) {
        REQUIRE(tri.id < stored.size());
        ++stored[tri.id];
        CHECK(same(tri.v0, vertices[3 * tri.id]));
        CHECK(same(tri.v1, vertices[3 * tri.id + 1]));
        CHECK(same(tri.v2, vertices[3 * tri.id + 2]));
    }
    uint32_t missing = 0;
    for (uint32_t c : stored) {
        CHECK(c <= 1);
        missing += c == 0 ? 1 : 0;
    }
    CHECK(missing == bvh.degenerate_triangles);
    CHECK(bvh.input_triangles == vertices.size() / 3);
}

std::string build_error(const Triangles& vertices, std::vector<uint32_t> ids = {}, BvhBuildOptions options = {}) {
    try {
        build_bvh(vertices, ids, options);
    } catch (const vplkit::Error& e) {
        return e.what();
    }
    return "";
}

// Triangles around the origin at geometrically shrinking distances and sizes: each SAH split
// peels the outer, large triangles off a dense core, which makes a deep chain.
Triangles shrinking_shells(uint32_t count) {
    std::mt19937 rng(7);
    Triangles out;
    for (uint32_t i = 0; i < count; ++i) {
        const float radius = std::exp2(-float(i) / 64.0f);
        const glm::vec3 centre = radius * vplkit::bvh_test::random_direction(rng);
        for (int k = 0; k < 3; ++k) {
            out.push_back(centre + 0.05f * radius * vplkit::bvh_test::random_direction(rng));
        }
    }
    return out;
}

}  // namespace

TEST_CASE("bvh build: random soup - every triangle in one leaf and every box contains its contents") {
    const Triangles soup = vplkit::bvh_test::random_soup(3000, 1);
    const Bvh bvh = build_bvh(soup);
    check_structure(bvh, soup);
    CHECK(bvh.triangles.size() == 3000);
    CHECK(bvh.degenerate_triangles == 0);
    MESSAGE("3000 triangles: " << bvh.nodes.size() << " nodes, depth " << bvh.depth << ", SAH cost " << bvh.sah_cost);
}

TEST_CASE("bvh build: closed meshes keep their structure") {
    for (const Triangles& mesh : {vplkit::bvh_test::icosphere(4), vplkit::bvh_test::grid_box(16)}) {
        const Bvh bvh = build_bvh(mesh);
        check_structure(bvh, mesh);
    }
}

TEST_CASE("bvh build: boxes are padded by the stated fraction of the scene scale") {
    const Triangles mesh = vplkit::bvh_test::transformed(vplkit::bvh_test::grid_box(2), 3.0f, {0, 0, 0});
    const Bvh bvh = build_bvh(mesh);
    const float pad = 3.0f * vplkit::kBvhBoxPadding;
    CHECK(bvh.nodes[0].lo.x == -3.0f - pad);
    CHECK(bvh.nodes[0].hi.z == 3.0f + pad);
    CHECK(bvh.scene_scale == 3.0f + pad);
}

TEST_CASE("bvh build: tiny and huge coordinates keep the structure") {
    // Centroids closer than the smallest normal float (binning must not divide by them), and
    // coordinates near the 2^32 limit.
    for (const float scale : {1e-39f, 1e-30f, 1e9f}) {
        CAPTURE(scale);
        const Triangles scene = vplkit::bvh_test::transformed(vplkit::bvh_test::random_soup(500, 9), scale, {0, 0, 0});
        const Bvh bvh = build_bvh(scene);
        check_structure(bvh, scene);
    }
}

TEST_CASE("bvh build: user ids are carried to the stored triangles") {
    const Triangles soup = vplkit::bvh_test::random_soup(100, 2);
    std::vector<uint32_t> ids(100);
    for (uint32_t i = 0; i < 100; ++i) {
        ids[i] = 1000 + 7 * i;
    }
    const Bvh bvh = build_bvh(soup, ids);
    std::vector<int> seen(100, 0);
    for (const auto& tri : bvh.triangles) {
        REQUIRE(tri.id >= 1000);
        const uint32_t i = (tri.id - 1000) / 7;
        REQUIRE((tri.id - 1000) % 7 == 0);
        REQUIRE(i < 100);
        ++seen[i];
        CHECK(same(tri.v0, soup[3 * i]));
        CHECK(same(tri.v2, soup[3 * i + 2]));
    }
    for (int s : seen) {
        CHECK(s == 1);
    }
}

TEST_CASE("bvh build: the depth cap holds for a scene SAH would chain deeply") {
    const Triangles shells = shrinking_shells(3000);
    const BvhBuildOptions defaults;  // the default cap (kBvhMaxDepth)
    const Bvh bvh = build_bvh(shells, {}, defaults);
    check_structure(bvh, shells);
    MESSAGE("shrinking shells: depth " << bvh.depth << ", " << bvh.median_splits << " median splits");

    // A cap far below what SAH wants: median splits take over where needed.
    BvhBuildOptions capped;
    capped.max_depth = 10;  // 4 * 2^10 = 4096 >= 3000 triangles
    const Bvh shallow = build_bvh(shells, {}, capped);
    check_structure(shallow, shells, 10);
    CHECK(shallow.median_splits > 0);
    CHECK(shallow.sah_cost > bvh.sah_cost);  // the cap costs quality

    // Exactly full: 4 * 2^9 = 2048 triangles in depth 9 leaves only in a perfect median tree.
    capped.max_depth = 9;
    const Triangles full(shells.begin(), shells.begin() + 3 * 2048);
    const Bvh perfect = build_bvh(full, {}, capped);
    check_structure(perfect, full, 9);
    CHECK(perfect.leaf_count == 512);

    const Triangles too_many(shells.begin(), shells.begin() + 3 * 2049);
    CHECK(build_error(too_many, {}, capped).find("do not fit") != std::string::npos);
}

TEST_CASE("bvh build: split - masked triangles in a subtree of their own under node 0") {
    const Triangles soup = vplkit::bvh_test::random_soup(3000, 5);
    std::vector<uint8_t> masked(3000, 0);
    for (uint32_t t = 0; t < 3000; t += 3) masked[t] = 1;
    const Bvh bvh = vplkit::build_bvh_split(soup, masked);
    check_structure(bvh, soup);
    REQUIRE(bvh.masked_root > 1);
    CHECK(!bvh_is_leaf(bvh.nodes[0]));
    CHECK(bvh.nodes[0].index == bvh.masked_root);
    CHECK(bvh.opaque_triangles == 2000);
    for (uint32_t i = 0; i < bvh.triangles.size(); ++i) {
        CHECK((i >= bvh.opaque_triangles) == (masked[bvh.triangles[i].id] != 0));
    }
    // Every triangle of each subtree's leaves is on its side of opaque_triangles.
    std::vector<uint32_t> stack = {1u, bvh.masked_root};
    std::vector<bool> masked_side = {false, true};
    while (!stack.empty()) {
        const BvhNode& node = bvh.nodes[stack.back()];
        const bool side = masked_side.back();
        const uint32_t index = stack.back();
        stack.pop_back();
        masked_side.pop_back();
        if (bvh_is_leaf(node)) {
            for (uint32_t i = node.index; i < node.index + bvh_leaf_triangles(node); ++i) {
                CHECK((i >= bvh.opaque_triangles) == side);
            }
        } else {
            stack.insert(stack.end(), {index + 1, node.index});
            masked_side.insert(masked_side.end(), {side, side});
        }
    }

    // No split without both kinds: exactly build_bvh's tree.
    const Bvh plain = build_bvh(soup);
    for (uint8_t flag : {0, 1}) {
        const Bvh one = vplkit::build_bvh_split(soup, std::vector<uint8_t>(3000, flag));
        CHECK(one.masked_root == 0);
        REQUIRE(one.nodes.size() == plain.nodes.size());
        CHECK(std::memcmp(one.nodes.data(), plain.nodes.data(), plain.nodes.size() * sizeof(BvhNode)) == 0);
        CHECK(std::memcmp(one.triangles.data(), plain.triangles.data(),
                          plain.triangles.size() * sizeof(plain.triangles[0])) == 0);
    }
    // The depth cap holds below the common root; where the split would break it, one tree.
    const Triangles shells = shrinking_shells(3000);
    BvhBuildOptions capped;
    capped.max_depth = 10;  // each subtree 9 levels: 4 * 2^9 >= 1500
    std::vector<uint8_t> alternate(3000, 0);
    for (uint32_t t = 0; t < 3000; t += 2) alternate[t] = 1;
    const Bvh deep = vplkit::build_bvh_split(shells, alternate, {}, capped);
    check_structure(deep, shells, 10);
    CHECK(deep.masked_root != 0);
    capped.max_depth = 9;  // 2048 triangles fit only as one tree: 1984 opaque ones need 9 levels
    const Triangles full(shells.begin(), shells.begin() + 3 * 2048);
    std::vector<uint8_t> few(2048, 0);
    for (uint32_t t = 0; t < 64; ++t) few[t] = 1;
    const Bvh one = vplkit::build_bvh_split(full, few, {}, capped);
    check_structure(one, full, 9);
    CHECK(one.masked_root == 0);
    CHECK_THROWS_AS(vplkit::build_bvh_split(soup, std::vector<uint8_t>(2999, 0)), vplkit::Error);
}

TEST_CASE("bvh build: SAH separates distant clusters at the root and beats median splits") {
    Triangles scene = vplkit::bvh_test::transformed(vplkit::bvh_test::random_soup(300, 3, 0.05f), 1.0f, {-50, 0, 0});
    const Triangles right =
        vplkit::bvh_test::transformed(vplkit::bvh_test::random_soup(100, 4, 0.05f), 1.0f, {50, 0, 0});
    scene.insert(scene.end(), right.begin(), right.end());
    const Bvh bvh = build_bvh(scene);
    check_structure(bvh, scene);
    const BvhNode& first = bvh.nodes[1];
    const BvhNode& second = bvh.nodes[bvh.nodes[0].index];
    // Uneven counts (300 vs 100): a median split would cut the left cluster; SAH cuts the gap.
    CHECK(std::max(first.lo.x, second.lo.x) > 0.0f);
    CHECK(std::min(first.hi.x, second.hi.x) < 0.0f);

    BvhBuildOptions median;
    median.max_depth = 7;  // 4 * 2^7 = 512 >= 400: nearly every split is forced to the median
    CHECK(build_bvh(scene, {}, median).sah_cost > bvh.sah_cost);
}

TEST_CASE("bvh build: non-finite vertices are refused naming the triangle") {
    Triangles soup = vplkit::bvh_test::random_soup(10, 5);
    soup[3 * 6 + 2].y = std::numeric_limits<float>::quiet_NaN();
    std::string message = build_error(soup);
    CHECK(message.find("triangle 6") != std::string::npos);
    CHECK(message.find("non-finite") != std::string::npos);

    soup = vplkit::bvh_test::random_soup(10, 5);
    soup[3 * 4].x = -std::numeric_limits<float>::infinity();
    message = build_error(soup);
    CHECK(message.find("triangle 4") != std::string::npos);
    CHECK(message.find("non-finite") != std::string::npos);

    soup = vplkit::bvh_test::random_soup(10, 5);
    soup[3 * 9 + 1].z = 5e9f;
    message = build_error(soup);
    CHECK(message.find("triangle 9") != std::string::npos);
    CHECK(message.find("2^32") != std::string::npos);
}

TEST_CASE("bvh build: malformed input and options are refused") {
    Triangles soup = vplkit::bvh_test::random_soup(4, 6);
    soup.pop_back();
    CHECK(build_error(soup).find("whole number of triangles") != std::string::npos);
    soup = vplkit::bvh_test::random_soup(4, 6);
    CHECK(build_error(soup, {1, 2, 3}).find("3 triangle ids for 4 triangles") != std::string::npos);
    CHECK(build_error(soup, {1, 2, vplkit::kBvhNoHit, 3}).find("triangle 2 has id 0xffffffff") != std::string::npos);
    BvhBuildOptions options;
    options.max_depth = vplkit::kBvhMaxDepth + 1;
    CHECK(build_error(soup, {}, options).find("max_depth") != std::string::npos);
    options = {};
    options.max_leaf_triangles = 5;
    CHECK(build_error(soup, {}, options).find("max_leaf_triangles") != std::string::npos);
    options = {};
    options.bins = 1;
    CHECK(build_error(soup, {}, options).find("bins") != std::string::npos);
    options = {};
    options.triangle_cost = 0.0f;
    CHECK(build_error(soup, {}, options).find("cost") != std::string::npos);
}

TEST_CASE("bvh build: degenerate triangles are left out and counted") {
    Triangles scene = vplkit::bvh_test::random_soup(20, 8);
    const glm::vec3 p(0.25f, -0.5f, 0.125f), q(1.0f, 2.0f, 3.0f);
    // Triangle 20: one point three times; 21: two coincident vertices; 22: collinear (exact).
    scene.insert(scene.end(), {p, p, p, p, p, q, p, q, 2.0f * q - p});
    const Bvh bvh = build_bvh(scene);
    check_structure(bvh, scene);
    CHECK(bvh.degenerate_triangles == 3);
    CHECK(bvh.triangles.size() == 20);
    for (const auto& tri : bvh.triangles) {
        CHECK(tri.id < 20);
    }
}

TEST_CASE("bvh build: the empty scene is one leaf without triangles") {
    for (const Triangles& scene : {Triangles{}, Triangles{{1, 1, 1}, {1, 1, 1}, {2, 2, 2}}}) {
        const Bvh bvh = build_bvh(scene);
        REQUIRE(bvh.nodes.size() == 1);
        CHECK(bvh_is_leaf(bvh.nodes[0]));
        CHECK(bvh_leaf_triangles(bvh.nodes[0]) == 0);
        CHECK(bvh.triangles.empty());
        CHECK(bvh.leaf_count == 1);
        CHECK(bvh.depth == 0);
        CHECK(bvh.scene_scale == vplkit::kBvhMinScale);
    }
}

TEST_CASE("bvh build: one triangle is one leaf") {
    const Triangles one = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const Bvh bvh = build_bvh(one);
    check_structure(bvh, one);
    REQUIRE(bvh.nodes.size() == 1);
    CHECK(bvh_leaf_triangles(bvh.nodes[0]) == 1);
    CHECK(bvh.triangles[0].id == 0);
}
