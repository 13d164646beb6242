// light_tree_leaves.comp + light_tree_levels.comp against the double-precision reference in
// tests/reference/light_tree_reference.cpp, every field of every node.
//
// Tolerances:
// - Boxes and VPL counts must match exactly: min/max of floats and integer sums do not round.
// - Intensities are sums of non-negative floats. A leaf rounds twice ((r + g) + b), and each
//   level above adds one rounding, so a node of height h is within (1 + u)^(h + 2) - 1 of the
//   exact sum, relatively (u = 2^-24, the float unit roundoff; the standard bound for recursive
//   summation of non-negative terms). An exact zero must stay exactly zero.
// - The tree's own invariants are exact: a parent's box is the union of its children's, its
//   count their sum, and its intensity the float sum left + right of theirs, because
//   light_tree_levels.comp sums in tree order whatever the group size (so is every leaf's
//   intensity the float (r + g) + b of its flux).
// - Nothing is Inf or NaN; the empty box [+FLT_MAX, -FLT_MAX] appears on bogus subtrees only.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/device_info.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/stages/light_tree.hpp"
#include "vplkit_test/context.hpp"
#include "light_tree_reference.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using vplkit::shaders::LightTreeNode;
using vplkit::shaders::vec3;
using vplkit::shaders::Vpl;
using RefVpl = vplkit::reference::LightTreeVpl;
using RefNode = vplkit::reference::LightTreeNode;

constexpr float kFloatMax = std::numeric_limits<float>::max();
constexpr double kUnitRoundoff = 0x1p-24;

enum class BogusData { zero, garbage };

float axis(const vec3& v, int a) {
    return a == 0 ? v.x : (a == 1 ? v.y : v.z);
}

// The leaf array as gather_leaves.comp leaves it: the real VPLs, then bogus slots up to a power
// of two. Bogus slots hold zeros or, to show they are told by index, bright VPLs far away.
std::vector<Vpl> make_leaves(const std::vector<RefVpl>& vpls, BogusData bogus) {
    const uint32_t leaf_count = vplkit::stages::light_tree_leaf_count(uint32_t(vpls.size()));
    std::vector<Vpl> leaves(leaf_count);
    for (size_t i = 0; i < leaves.size(); ++i) {
        Vpl& leaf = leaves[i];
        if (i < vpls.size()) {
            leaf.position = {vpls[i].position[0], vpls[i].position[1], vpls[i].position[2]};
            leaf.normal = {0.0f, 0.0f, 1.0f};
            leaf.flux = {vpls[i].flux[0], vpls[i].flux[1], vpls[i].flux[2]};
        } else if (bogus == BogusData::garbage) {
            const float far = 1e30f * float(i + 1);
            leaf.position = {-far, far, -far};
            leaf.normal = {1.0f, 0.0f, 0.0f};
            leaf.flux = {1e20f, 1e20f, 1e20f};
        }
    }
    return leaves;
}

std::vector<LightTreeNode> gpu_tree(const std::vector<Vpl>& leaves, uint32_t count,
                                    const vplkit::stages::LightTreeOptions& options = {}) {
    vplkit::Context& ctx = vplkit::test::context();
    const uint32_t node_count = vplkit::stages::light_tree_node_count(count);
    auto leaf_buffer = vplkit::Buffer::create(ctx, leaves.size() * sizeof(Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                              vplkit::MemoryUse::device, "leaves");
    auto nodes = vplkit::Buffer::create(ctx, node_count * sizeof(LightTreeNode), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vplkit::MemoryUse::device, "light tree");
    leaf_buffer.upload(leaves);
    // Garbage first (0xffffffff words are NaNs), so a node the build misses cannot pass.
    nodes.upload(std::vector<uint8_t>(node_count * sizeof(LightTreeNode), 0xff));

    vplkit::PassList passes("light tree test");
    vplkit::stages::add_light_tree_passes(ctx, passes, leaf_buffer, nodes, count, options);
    passes.run(ctx);
    return nodes.download<LightTreeNode>(node_count);
}

std::vector<LightTreeNode> gpu_tree(const std::vector<RefVpl>& vpls, BogusData bogus = BogusData::garbage,
                                    const vplkit::stages::LightTreeOptions& options = {}) {
    return gpu_tree(make_leaves(vpls, bogus), uint32_t(vpls.size()), options);
}

bool finite(const LightTreeNode& node) {
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(axis(node.box_min, a)) || !std::isfinite(axis(node.box_max, a))) {
            return false;
        }
    }
    return std::isfinite(node.intensity);
}

bool is_empty_box(const LightTreeNode& node) {
    for (int a = 0; a < 3; ++a) {
        if (axis(node.box_min, a) != kFloatMax || axis(node.box_max, a) != -kFloatMax) {
            return false;
        }
    }
    return true;
}

std::string describe(const LightTreeNode& node) {
    return "box [" + std::to_string(node.box_min.x) + " " + std::to_string(node.box_min.y) + " " +
           std::to_string(node.box_min.z) + "] - [" + std::to_string(node.box_max.x) + " " +
           std::to_string(node.box_max.y) + " " + std::to_string(node.box_max.z) + "] intensity " +
           std::to_string(node.intensity) + " vpls " + std::to_string(node.vpl_count);
}

// Every node against the reference; reports the first few mismatches and how many there were.
void check_against_reference(const std::vector<LightTreeNode>& gpu, const std::vector<RefVpl>& vpls) {
    const std::vector<RefNode> ref = vplkit::reference::light_tree(vpls);
    REQUIRE(gpu.size() == ref.size());
    size_t failures = 0;
    auto fail = [&failures](size_t n, const LightTreeNode& node, const char* what) {
        if (++failures <= 5) {
            MESSAGE("node " << n << ": " << what << " (" << describe(node) << ")");
        }
    };
    for (size_t n = 0; n < gpu.size(); ++n) {
        const LightTreeNode& node = gpu[n];
        const RefNode& expected = ref[n];
        if (!finite(node)) {
            fail(n, node, "not finite");
            continue;
        }
        if (node.vpl_count != expected.vpl_count) {
            fail(n, node, "VPL count differs");
        }
        if (expected.empty) {
            if (!is_empty_box(node) || node.intensity != 0.0f) {
                fail(n, node, "bogus subtree without the empty box and zero intensity");
            }
            continue;
        }
        for (int a = 0; a < 3; ++a) {
            if (double(axis(node.box_min, a)) != expected.box_min[a] ||
                double(axis(node.box_max, a)) != expected.box_max[a]) {
                fail(n, node, "box differs");
                break;
            }
        }
        const double tolerance = std::pow(1.0 + kUnitRoundoff, double(expected.height) + 2.0) - 1.0;
        const double error = std::abs(double(node.intensity) - expected.intensity);
        if (expected.intensity == 0.0 ? node.intensity != 0.0f : error > tolerance * expected.intensity) {
            fail(n, node, ("intensity off the reference " + std::to_string(expected.intensity)).c_str());
        }
    }
    CHECK_MESSAGE(failures == 0, failures << " of " << gpu.size() << " nodes differ from the reference");
}

// The tree's own invariants, exact (see the file comment); `leaves` is what the build read.
void check_invariants(const std::vector<LightTreeNode>& gpu, const std::vector<Vpl>& leaves, uint32_t count) {
    const size_t leaf_count = leaves.size();
    REQUIRE(gpu.size() == 2 * leaf_count - 1);
    size_t failures = 0;
    auto fail = [&failures](size_t n, const LightTreeNode& node, const char* what) {
        if (++failures <= 5) {
            MESSAGE("node " << n << ": " << what << " (" << describe(node) << ")");
        }
    };
    for (size_t n = 0; n < gpu.size(); ++n) {
        const LightTreeNode& node = gpu[n];
        if (!finite(node)) {
            fail(n, node, "not finite");
            continue;
        }
        // Only bogus subtrees carry the empty box; every real box is a proper (maybe flat) box.
        if (node.vpl_count == 0) {
            if (!is_empty_box(node) || node.intensity != 0.0f) {
                fail(n, node, "bogus without the empty box");
            }
        } else {
            for (int a = 0; a < 3; ++a) {
                if (!(axis(node.box_min, a) <= axis(node.box_max, a)) || std::abs(axis(node.box_min, a)) == kFloatMax ||
                    std::abs(axis(node.box_max, a)) == kFloatMax) {
                    fail(n, node, "real node with an inverted or sentinel box");
                    break;
                }
            }
        }
        if (n >= leaf_count - 1) {
            const size_t leaf = n - (leaf_count - 1);
            const Vpl& vpl = leaves[leaf];
            if (leaf < count) {
                const bool at_vpl = node.box_min.x == vpl.position.x && node.box_min.y == vpl.position.y &&
                                    node.box_min.z == vpl.position.z && node.box_max.x == vpl.position.x &&
                                    node.box_max.y == vpl.position.y && node.box_max.z == vpl.position.z;
                const float intensity = (vpl.flux.x + vpl.flux.y) + vpl.flux.z;
                if (!at_vpl || node.intensity != intensity || node.vpl_count != 1) {
                    fail(n, node, "real leaf is not its VPL");
                }
            } else if (node.vpl_count != 0) {
                fail(n, node, "bogus leaf counted as a VPL");
            }
            continue;
        }
        const LightTreeNode& left = gpu[2 * n + 1];
        const LightTreeNode& right = gpu[2 * n + 2];
        bool box_ok = true;
        for (int a = 0; a < 3; ++a) {
            box_ok = box_ok && axis(node.box_min, a) == std::min(axis(left.box_min, a), axis(right.box_min, a)) &&
                     axis(node.box_max, a) == std::max(axis(left.box_max, a), axis(right.box_max, a));
        }
        if (!box_ok) {
            fail(n, node, "box is not the union of the children's");
        }
        if (node.intensity != left.intensity + right.intensity) {
            fail(n, node, "intensity is not the float sum of the children's");
        }
        if (node.vpl_count != left.vpl_count + right.vpl_count) {
            fail(n, node, "VPL count is not the sum of the children's");
        }
    }
    CHECK_MESSAGE(failures == 0, failures << " of " << gpu.size() << " nodes break the tree invariants");
}

// Builds the tree of `vpls` (bogus slots full of garbage) and checks it every way.
std::vector<LightTreeNode> check_tree(const std::vector<RefVpl>& vpls,
                                      const vplkit::stages::LightTreeOptions& options = {}) {
    const std::vector<Vpl> leaves = make_leaves(vpls, BogusData::garbage);
    std::vector<LightTreeNode> gpu = gpu_tree(leaves, uint32_t(vpls.size()), options);
    check_against_reference(gpu, vpls);
    check_invariants(gpu, leaves, uint32_t(vpls.size()));
    return gpu;
}

std::vector<RefVpl> random_vpls(uint32_t count, uint32_t seed, float extent = 10.0f, float offset = 0.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> position(-extent, extent);
    std::uniform_real_distribution<float> flux(0.0f, 5.0f);
    std::vector<RefVpl> vpls(count);
    for (RefVpl& vpl : vpls) {
        vpl.position = {offset + position(rng), offset + position(rng), offset + position(rng)};
        vpl.flux = {flux(rng), flux(rng), flux(rng)};
    }
    return vpls;
}

bool same_node(const LightTreeNode& a, const LightTreeNode& b) {
    for (int i = 0; i < 3; ++i) {
        if (axis(a.box_min, i) != axis(b.box_min, i) || axis(a.box_max, i) != axis(b.box_max, i)) {
            return false;
        }
    }
    return a.intensity == b.intensity && a.vpl_count == b.vpl_count;
}

}  // namespace

TEST_CASE("light tree: random VPLs at 1 2 3 64 65 1000 4096 and 4097 match the reference") {
    for (uint32_t count : {1u, 2u, 3u, 64u, 65u, 1000u, 4096u, 4097u}) {
        CAPTURE(count);
        check_tree(random_vpls(count, count));
    }
}

TEST_CASE("light tree: node and leaf counts") {
    using vplkit::stages::light_tree_leaf_count;
    using vplkit::stages::light_tree_node_count;
    CHECK(light_tree_leaf_count(1) == 1);
    CHECK(light_tree_node_count(1) == 1);
    CHECK(light_tree_leaf_count(2) == 2);
    CHECK(light_tree_node_count(3) == 7);
    CHECK(light_tree_node_count(4096) == 8191);
    CHECK(light_tree_node_count(4097) == 16383);
    CHECK(light_tree_node_count(vplkit::stages::kLightTreeMaxLeaves) == 0xffffffffu);
}

TEST_CASE("light tree: a single VPL is the root") {
    const std::vector<RefVpl> vpls{{{1.5f, -2.0f, 3.25f}, {0.5f, 0.25f, 2.0f}}};
    const auto gpu = check_tree(vpls);
    REQUIRE(gpu.size() == 1);
    CHECK(gpu[0].box_min.x == 1.5f);
    CHECK(gpu[0].box_max.z == 3.25f);
    CHECK(gpu[0].intensity == 2.75f);
    CHECK(gpu[0].vpl_count == 1);
}

TEST_CASE("light tree: bogus padding - 5 VPLs and 3 bogus leaves - told by index not by data") {
    const std::vector<RefVpl> vpls = random_vpls(5, 7);
    const auto with_garbage = gpu_tree(vpls, BogusData::garbage);
    const auto with_zeros = gpu_tree(vpls, BogusData::zero);
    check_against_reference(with_garbage, vpls);
    check_invariants(with_garbage, make_leaves(vpls, BogusData::garbage), 5);
    REQUIRE(with_garbage.size() == 15);
    for (size_t n = 0; n < with_garbage.size(); ++n) {
        CAPTURE(n);
        CHECK(same_node(with_garbage[n], with_zeros[n]));
    }
    // Leaves 5..7 are nodes 12..14; node 6 covers leaves 6 and 7 only.
    for (size_t n : {12u, 13u, 14u, 6u}) {
        CAPTURE(n);
        CHECK(with_garbage[n].vpl_count == 0);
        CHECK(with_garbage[n].intensity == 0.0f);
        CHECK(is_empty_box(with_garbage[n]));
    }
    // Node 5 has the real leaf 4 (node 11) and the bogus leaf 5: exactly the real child.
    CHECK(same_node(with_garbage[5], with_garbage[11]));
    CHECK(with_garbage[5].box_min.x == vpls[4].position[0]);
    CHECK(with_garbage[5].box_max.y == vpls[4].position[1]);
    // The root's box is that of the five VPLs alone.
    float max_x = vpls[0].position[0];
    for (const RefVpl& vpl : vpls) max_x = std::max(max_x, vpl.position[0]);
    CHECK(with_garbage[0].box_max.x == max_x);
    CHECK(with_garbage[0].vpl_count == 5);
}

TEST_CASE("light tree: coincident VPLs give zero-extent boxes") {
    // 300 VPLs on one point, then 200 on another: every box is a point except those spanning both.
    std::vector<RefVpl> vpls(500);
    for (size_t i = 0; i < vpls.size(); ++i) {
        vpls[i].position = i < 300 ? std::array<float, 3>{0.1f, -7.0f, 3.0f} : std::array<float, 3>{2.0f, 2.0f, 2.0f};
        vpls[i].flux = {0.3f, 0.2f, 0.1f};
    }
    const auto gpu = check_tree(vpls);
    // 512 leaves: node 1 covers leaves 0..255, which all sit on the first point.
    const LightTreeNode& cluster = gpu[1];
    CHECK(cluster.vpl_count == 256);
    CHECK(cluster.box_min.x == cluster.box_max.x);
    CHECK(cluster.box_min.y == cluster.box_max.y);
    CHECK(cluster.box_min.z == cluster.box_max.z);
    CHECK(cluster.box_min.y == -7.0f);
}

TEST_CASE("light tree: intensities from 1e-6 to 1e6 in one tree") {
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> exponent(-6.0f, 6.0f);
    std::vector<RefVpl> vpls = random_vpls(4097, 99);
    for (RefVpl& vpl : vpls) {
        // Log-uniform channels, and a few VPLs at the extremes side by side.
        vpl.flux = {std::pow(10.0f, exponent(rng)), std::pow(10.0f, exponent(rng)), std::pow(10.0f, exponent(rng))};
    }
    for (size_t i = 0; i < 64; i += 2) {
        vpls[i].flux = {1e-6f, 1e-6f, 1e-6f};
        vpls[i + 1].flux = {1e6f, 1e6f, 1e6f};
    }
    const auto gpu = check_tree(vpls);
    // Where a subtree holds only the smallest VPLs, the sum is not swallowed by anything.
    vpls.assign(64, RefVpl{{0.0f, 0.0f, 0.0f}, {1e-6f, 1e-6f, 1e-6f}});
    vpls.push_back({{1.0f, 1.0f, 1.0f}, {1e6f, 1e6f, 1e6f}});
    const auto small_and_big = check_tree(vpls);
    CHECK(small_and_big[1].intensity == doctest::Approx(64 * 3e-6).epsilon(1e-6));  // leaves 0..63
}

TEST_CASE("light tree: scenes at 1e-3 and 1e4 scale - off the origin") {
    check_tree(random_vpls(1000, 5, 1e-3f));
    check_tree(random_vpls(1000, 6, 1e-3f, 0.5f));
    check_tree(random_vpls(1000, 7, 1e4f));
    check_tree(random_vpls(1000, 8, 1e4f, -3e4f));
}

TEST_CASE("light tree: zero-flux real VPLs are real - counted and bounded - with zero intensity") {
    std::vector<RefVpl> vpls = random_vpls(100, 11);
    // Leaves 0..31 are all black: their subtree becomes a dead branch with a real box.
    // Scattered black VPLs elsewhere.
    for (size_t i = 0; i < 32; ++i) vpls[i].flux = {0.0f, 0.0f, 0.0f};
    for (size_t i = 40; i < 100; i += 7) vpls[i].flux = {0.0f, 0.0f, 0.0f};
    // The black VPL 99 (the last real leaf) lies far out: the root's box must reach it.
    vpls[99].flux = {0.0f, 0.0f, 0.0f};
    vpls[99].position = {500.0f, -500.0f, 500.0f};
    const auto gpu = check_tree(vpls);
    // 128 leaves: level 2 nodes 3..6 cover 32 leaves each; node 3 is leaves 0..31.
    const LightTreeNode& dead = gpu[3];
    CHECK(dead.vpl_count == 32);
    CHECK(dead.intensity == 0.0f);
    CHECK_FALSE(is_empty_box(dead));
    CHECK(dead.box_min.x < dead.box_max.x);
    const LightTreeNode& black_leaf = gpu[127 + 99];
    CHECK(black_leaf.vpl_count == 1);
    CHECK(black_leaf.intensity == 0.0f);
    CHECK(gpu[0].box_max.x == 500.0f);
    CHECK(gpu[0].box_min.y == -500.0f);
}

TEST_CASE("light tree: every group size and workgroup size builds the same tree") {
    for (uint32_t count : {1000u, 4097u}) {
        CAPTURE(count);
        const std::vector<RefVpl> vpls = random_vpls(count, 3 * count);
        vplkit::stages::LightTreeOptions options;
        options.group_levels = 1;
        const auto level_by_level = check_tree(vpls, options);
        for (uint32_t group_levels = 2; group_levels <= vplkit::stages::kLightTreeMaxGroupLevels; ++group_levels) {
            for (uint32_t workgroup_size : {32u, 256u}) {
                CAPTURE(group_levels);
                CAPTURE(workgroup_size);
                options.group_levels = group_levels;
                options.workgroup_size = workgroup_size;
                const auto grouped = gpu_tree(vpls, BogusData::garbage, options);
                REQUIRE(grouped.size() == level_by_level.size());
                size_t differing = 0;
                for (size_t n = 0; n < grouped.size(); ++n) {
                    differing += same_node(grouped[n], level_by_level[n]) ? 0 : 1;
                }
                CHECK(differing == 0);
            }
        }
    }
}

TEST_CASE("light tree: more than 65,535 workgroups (a grid folded into rows) match the reference") {
    // Workgroups of 1 thread and 70,000 VPLs: 131,072 leaves, one thread each, so 131,072
    // workgroups, past 65,535 (maxComputeWorkGroupCount's minimum, lavapipe's limit): the
    // generated dispatch folds them into 3 rows of 43,691. Before the fold this was refused
    // ("raise the workgroup size").
    vplkit::stages::LightTreeOptions options;
    options.workgroup_size = 1;
    check_tree(random_vpls(70000, 27), options);
}

TEST_CASE("light tree: the dispatch schedule") {
    using vplkit::stages::light_tree_dispatch_count;
    CHECK(light_tree_dispatch_count(1, 4) == 1);         // the root is the leaf
    CHECK(light_tree_dispatch_count(2, 4) == 2);         // leaves, one group of one level
    CHECK(light_tree_dispatch_count(65536, 4) == 5);     // 16 levels: 4 groups of 4
    CHECK(light_tree_dispatch_count(65537, 4) == 6);     // 17 levels: 4 x 4 + 1
    CHECK(light_tree_dispatch_count(1u << 20, 3) == 8);  // 20 levels: 6 x 3 + 2
    CHECK(light_tree_dispatch_count(4096, 1) == 13);
    CHECK_THROWS_AS(light_tree_dispatch_count(4096, 0), vplkit::Error);
    CHECK_THROWS_AS(light_tree_dispatch_count(4096, 9), vplkit::Error);
}

TEST_CASE("light tree: the default group size follows the device type") {
    vplkit::stages::Limits device;
    device.cpu = true;
    CHECK(vplkit::stages::light_tree_default_group_levels(device) == 1);
    device.cpu = false;
    CHECK(vplkit::stages::light_tree_default_group_levels(device) == 4);
    // Group size 0 (the default) builds the same tree as an explicit one.
    const std::vector<RefVpl> vpls = random_vpls(300, 17);
    vplkit::stages::LightTreeOptions options;
    options.group_levels = 3;
    const auto explicit_groups = gpu_tree(vpls, BogusData::garbage, options);
    const auto default_groups = check_tree(vpls);
    for (size_t n = 0; n < explicit_groups.size(); ++n) {
        CAPTURE(n);
        CHECK(same_node(explicit_groups[n], default_groups[n]));
    }
}

TEST_CASE("light tree: bad input is refused with a clear message") {
    vplkit::Context& ctx = vplkit::test::context();
    auto leaves = vplkit::Buffer::create(ctx, 8 * sizeof(Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vplkit::MemoryUse::device, "leaves");
    auto nodes = vplkit::Buffer::create(ctx, 15 * sizeof(LightTreeNode), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vplkit::MemoryUse::device, "nodes");
    auto small = vplkit::Buffer::create(ctx, 14 * sizeof(LightTreeNode), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vplkit::MemoryUse::device, "small");
    vplkit::PassList passes;
    using vplkit::stages::add_light_tree_passes;
    CHECK_THROWS_WITH_AS(add_light_tree_passes(ctx, passes, leaves, nodes, 0), doctest::Contains("count 0 is outside"),
                         vplkit::Error);
    CHECK_THROWS_WITH_AS(add_light_tree_passes(ctx, passes, leaves, nodes, vplkit::stages::kLightTreeMaxLeaves + 1),
                         doctest::Contains("is outside 1..2147483648"), vplkit::Error);
    CHECK_THROWS_WITH_AS(add_light_tree_passes(ctx, passes, leaves, small, 5),
                         doctest::Contains("buffer 'small' holds fewer than the 15 nodes"), vplkit::Error);
    CHECK_THROWS_WITH_AS(add_light_tree_passes(ctx, passes, small, nodes, 9),
                         doctest::Contains("buffer 'small' holds fewer than the 16 leaves"), vplkit::Error);
    vplkit::stages::LightTreeOptions options;
    options.group_levels = 9;
    CHECK_THROWS_WITH_AS(add_light_tree_passes(ctx, passes, leaves, nodes, 5, options),
                         doctest::Contains("group_levels 9 is outside 0..8"), vplkit::Error);
    options.group_levels = 4;
    options.workgroup_size = 0;
    CHECK_THROWS_WITH_AS(add_light_tree_passes(ctx, passes, leaves, nodes, 5, options),
                         doctest::Contains("workgroup size 0 is outside"), vplkit::Error);
    CHECK(passes.size() == 0);
}
