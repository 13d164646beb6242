// build_sst.comp on lavapipe against the double-precision reference (tests/reference/sst_reference).
//
// Tolerance: every float field must lie within 4x the reference's first-order rounding bound
// for that node (SstErrorBound). The bound is built merge by merge: ~1 ulp per float operation,
// the children's errors carried up, position errors scaled by the magnitudes involved (|mean|,
// the distance between the child means), normal errors divided by the merged normal's length
// before renormalization, frame errors by the frame's conditioning (|cross(h, n)| >= 0.43), and
// nu/variance errors from those. So it grows like log2(n) merges x float eps x the node's own
// scale, whether the scene is 1e-3 wide, 1e4 wide or far from the origin, and whether weights
// span 1e-6..1e6; the factor 4 covers second-order terms and inversesqrt's 2-ulp accuracy.
// Boxes, leaf counts and the fallback flag are compared exactly (min/max of the input floats
// and integer sums are exact). The suitability flag is compared wherever the reference's nu
// and sigma_z are farther from the thresholds than their bound; near a threshold either
// answer is right, and such nodes must stay rare.
// The harness (VPL sets, the GPU build, the comparison) is sst_build_check.cpp; the suitability
// flags on surfaces and sigma_max are test_build_sst_surfaces.cpp's.
#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit_test/context.hpp"
#include "sst_build_check.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace vplkit::sst_test;

TEST_CASE("sst: the default thresholds are the thesis values") {
    SstOptions options;
    CHECK(options.nu_min == 0.7f);
    CHECK(options.sigma_max == 0.3f);
}

TEST_CASE("sst: node and counter counts of the perfect tree") {
    using vplkit::stages::sst_counter_count;
    using vplkit::stages::sst_node_count;
    CHECK(sst_node_count(1) == 1);  // the root record of a single leaf
    CHECK(sst_node_count(2) == 1);
    CHECK(sst_node_count(5) == 7);
    CHECK(sst_node_count(1024) == 1023);
    CHECK(sst_node_count(1025) == 2047);
    CHECK(sst_counter_count(1) == 1);
    CHECK(sst_counter_count(2) == 1);
    CHECK(sst_counter_count(4) == 1);
    CHECK(sst_counter_count(8) == 3);
    CHECK(sst_counter_count(1025) == 1023);
}

TEST_CASE("sst: random scenes match the double reference at 2^k and 2^k + 1 counts") {
    for (uint32_t count : {1u, 2u, 3u, 4u, 5u, 7u, 8u, 9u, 16u, 17u, 255u, 256u, 257u, 1024u, 1025u}) {
        CAPTURE(count);
        const Scene scene = random_scene({.count = count, .seed = count});
        const Comparison c = build_and_compare(scene);
        CHECK(c.ambiguous_flags <= c.nodes / 50);
    }
}

TEST_CASE("sst: one VPL is the root record") {
    const Scene scene = padded({make_vpl({1.5f, -2.0f, 3.25f}, {0.0f, 2.0f, 0.0f}, {1.0f, 2.0f, 3.0f})});
    const auto gpu = build_on_gpu(scene);
    REQUIRE(gpu.size() == 1);
    const SstNode& root = gpu[0];
    CHECK(exact3(root.mean, {1.5, -2.0, 3.25}));
    CHECK(exact3(root.box_lo, {1.5, -2.0, 3.25}));
    CHECK(exact3(root.box_hi, {1.5, -2.0, 3.25}));
    CHECK(exact3(root.normal, {0.0, 1.0, 0.0}));  // renormalized
    CHECK(exact3(root.variance, {0.0, 0.0, 0.0}));
    CHECK(root.nu == 1.0f);
    CHECK(root.leaf_count == 1);
    CHECK(root.flags == 1u);  // suitable, no fallback
    CHECK(root.intensity == doctest::Approx(0.2126 + 2 * 0.7152 + 3 * 0.0722).epsilon(1e-6));
    compare_with_reference(scene, gpu, {});
}

TEST_CASE("sst: coincident VPLs have zero variance and a zero-extent box") {
    std::vector<Vpl> vpls;
    const std::array<float, 3> n = unit(1.0, -2.0, 0.5);
    for (int i = 0; i < 37; ++i) {
        vpls.push_back(make_vpl({123.25f, -7.5f, 0.125f}, n, {float(i % 5), 1.0f + i, 0.5f}));
    }
    const Scene scene = padded(vpls);
    for (const SstOptions& options : {kThesis, kPaper}) {
        const auto gpu = build_on_gpu(scene, options);
        for (size_t i = 0; i < gpu.size(); ++i) {
            CAPTURE(i);
            if (gpu[i].leaf_count == 0) continue;
            CHECK(exact3(gpu[i].mean, {123.25, -7.5, 0.125}));  // p1 + b * 0, exactly
            CHECK(exact3(gpu[i].variance, {0.0, 0.0, 0.0}));
            CHECK(exact3(gpu[i].box_lo, {123.25, -7.5, 0.125}));
            CHECK(exact3(gpu[i].box_hi, {123.25, -7.5, 0.125}));
            CHECK(gpu[i].nu == doctest::Approx(1.0).epsilon(1e-5));
            CHECK(gpu[i].flags == 1u);
        }
        CHECK(gpu[0].leaf_count == 37);
        compare_with_reference(scene, gpu, options);
    }
}

TEST_CASE("sst: anti-parallel normals fall back to the brighter child normal") {
    const std::array<float, 3> up{0.0f, 0.0f, 1.0f}, down{0.0f, 0.0f, -1.0f};
    SUBCASE("equal intensities keep the left child's normal") {
        const Scene scene = padded({make_vpl({0, 0, 0}, up, {1, 1, 1}), make_vpl({0, 0, 0}, down, {1, 1, 1})});
        const auto gpu = build_on_gpu(scene);
        CHECK(gpu[0].flags == 2u);  // fallback, not suitable
        CHECK(exact3(gpu[0].normal, {0.0, 0.0, 1.0}));
        CHECK(gpu[0].nu == 0.0f);
        CHECK(exact3(gpu[0].variance, {0.0, 0.0, 0.0}));
        compare_with_reference(scene, gpu, {});
    }
    SUBCASE("a slightly brighter right child gives its normal") {
        // a - b = -5e-5: the merged normal is far shorter than 1e-3
        const Scene scene =
            padded({make_vpl({0, 0, 0}, up, {1, 1, 1}), make_vpl({0, 0, 1}, down, {1.0001f, 1.0001f, 1.0001f})});
        const auto gpu = build_on_gpu(scene);
        CHECK(gpu[0].flags == 2u);
        CHECK(exact3(gpu[0].normal, {0.0, 0.0, -1.0}));
        CHECK(gpu[0].nu == 0.0f);
        compare_with_reference(scene, gpu, {});
    }
    SUBCASE("a clear imbalance renormalizes toward the brighter side") {
        // a - b = 1/3: long enough, no fallback, but nu = 0
        const Scene scene = padded({make_vpl({0, 0, 0}, up, {2, 2, 2}), make_vpl({0, 0, 0}, down, {1, 1, 1})});
        const auto gpu = build_on_gpu(scene, {.nu_min = 0.0f});
        CHECK((gpu[0].flags & 2u) == 0u);
        CHECK(near3(gpu[0].normal, {0.0, 0.0, 1.0}, 1e-6));
        CHECK(gpu[0].nu == 0.0f);
        compare_with_reference(scene, gpu, {.nu_min = 0.0f});
    }
    SUBCASE("a tree of opposing pairs stays finite and matches") {
        std::vector<Vpl> vpls;
        for (int i = 0; i < 21; ++i) {
            const float s = (i % 2 == 0) ? 1.0f : -1.0f;
            vpls.push_back(make_vpl({0.1f * float(i / 2), 0.0f, 0.0f}, unit(0.3 * s, 0.2 * s, s), {1, 1, 1}));
        }
        const Scene scene = padded(vpls);
        const auto gpu = build_on_gpu(scene);
        const Comparison c = compare_with_reference(scene, gpu, {});
        CHECK(c.fallbacks >= 10);
        for (const SstNode& n : gpu) CHECK(all_finite(n));
    }
}

TEST_CASE("sst: dark children get equal weights and intensity zero") {
    SUBCASE("an all-dark tree") {
        std::vector<Vpl> vpls;
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> u(-1.0f, 1.0f);
        for (int i = 0; i < 13; ++i) {
            vpls.push_back(make_vpl({u(rng), u(rng), u(rng)}, unit(u(rng), u(rng), 1.0), {0, 0, 0}));
        }
        const Scene scene = padded(vpls);
        const auto gpu = build_on_gpu(scene);
        for (const SstNode& n : gpu) {
            CHECK(n.intensity == 0.0f);
            CHECK(all_finite(n));
        }
        // Two dark leaves: the midpoint.
        const SstNode& first = gpu[vplkit::stages::leaf_count(13) / 2 - 1];
        const vec3& p0 = vpls[0].position;
        const vec3& p1 = vpls[1].position;
        CHECK(near3(first.mean, {0.5 * (p0.x + p1.x), 0.5 * (p0.y + p1.y), 0.5 * (p0.z + p1.z)}, 1e-6));
        compare_with_reference(scene, gpu, {});
    }
    SUBCASE("dark VPLs do not pull the mean or the normal") {
        std::vector<Vpl> vpls;
        for (int i = 0; i < 16; ++i) {
            const bool dark = i % 3 != 0;
            vpls.push_back(make_vpl({float(i), 0.0f, 0.0f}, dark ? unit(1, 0, 0) : unit(0, 0, 1),
                                    dark ? std::array<float, 3>{0, 0, 0} : std::array<float, 3>{1, 1, 1}));
        }
        const Scene scene = padded(vpls);
        const auto gpu = build_on_gpu(scene);
        // Bright ones at x = 0, 3, 6, 9, 12, 15: mean 7.5, normal +z; the box spans all 16.
        CHECK(near3(gpu[0].mean, {7.5, 0.0, 0.0}, 1e-5));
        CHECK(near3(gpu[0].normal, {0.0, 0.0, 1.0}, 1e-6));
        CHECK(exact3(gpu[0].box_lo, {0.0, 0.0, 0.0}));
        CHECK(exact3(gpu[0].box_hi, {15.0, 0.0, 0.0}));
        CHECK(gpu[0].nu == 0.0f);  // the dark VPLs' normals still count in nu
        compare_with_reference(scene, gpu, {});
    }
}

TEST_CASE("sst: bogus padding never moves a node") {
    // 9 VPLs: 16 leaves, the subtree of leaves 8..15 holds one real leaf, leaves 12..15 none.
    Scene scene = random_scene({.count = 9, .seed = 99});
    const auto clean = build_on_gpu(scene);
    compare_with_reference(scene, clean, {});

    // Leaf 8 is the only real leaf under node 2 (leaves 8..15), node 5 (8..11) and node 11
    // (8..9); node 6 (12..15) has only padding below.
    const auto one_leaf = ref::sst_leaf_node(reference_leaves(scene)[8], thresholds({}));
    for (uint32_t node : {2u, 5u, 6u, 11u}) {
        CAPTURE(node);
        if (node == 6u) {
            CHECK(is_all_zero(clean[node]));  // only padding below
            continue;
        }
        CHECK(exact3(clean[node].mean, one_leaf.mean));
        CHECK(exact3(clean[node].box_lo, one_leaf.box_lo));
        CHECK(exact3(clean[node].box_hi, one_leaf.box_hi));
        CHECK(exact3(clean[node].variance, {0.0, 0.0, 0.0}));
        CHECK(clean[node].nu == 1.0f);
        CHECK(clean[node].leaf_count == 1);
    }

    // Junk in the bogus leaves (huge, NaN): told apart by index, so nothing changes at all.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (uint32_t i = scene.count; i < scene.leaves.size(); ++i) {
        scene.leaves[i] = make_vpl({1e30f, nan, -1e30f}, {nan, 0, 0}, {1e30f, nan, 1e20f});
    }
    const auto junk = build_on_gpu(scene);
    REQUIRE(junk.size() == clean.size());
    for (size_t i = 0; i < junk.size(); ++i) {
        CAPTURE(i);
        CHECK(std::memcmp(&junk[i], &clean[i], offsetof(SstNode, _pad0)) == 0);
        CHECK(std::memcmp(&junk[i].colour, &clean[i].colour, sizeof(vec3)) == 0);
    }
}

TEST_CASE("sst: scenes at 1e-3 and 1e4 scale far from the origin match the reference") {
    // 1000 x the extent away from the origin: positions keep ~10 bits for the spread.
    for (double extent : {1e-3, 1.0, 1e4}) {
        CAPTURE(extent);
        const Scene scene = random_scene(
            {.count = 700, .seed = 5, .center = {1000 * extent, -700 * extent, 300 * extent}, .extent = extent});
        const Comparison c = build_and_compare(scene, {.nu_min = 0.7f, .sigma_max = float(0.3 * extent)});
        CHECK(c.ambiguous_flags <= c.nodes / 50);
    }
}

TEST_CASE("sst: intensities from 1e-6 to 1e6 keep variances non-negative and match") {
    for (uint32_t seed : {11u, 12u, 13u}) {
        CAPTURE(seed);
        const Scene scene = random_scene(
            {.count = 1000, .seed = seed, .extent = 10.0, .flux_lo = 1e-6, .flux_hi = 1e6, .log_flux = true});
        const Comparison c = build_and_compare(scene);
        CHECK(c.ambiguous_flags <= c.nodes / 50);
    }
}

TEST_CASE("sst: tree invariants hold on the GPU tree") {
    const Scene scene = random_scene({.count = 1000, .seed = 3, .extent = 5.0});
    const auto gpu = build_on_gpu(scene);
    const uint32_t leaves = uint32_t(scene.leaves.size());
    const auto ref_leaves = reference_leaves(scene);
    // A child as the GPU sees it: an inner node, or a leaf (as the reference makes it).
    auto child = [&](uint32_t c) {
        if (c < leaves - 1) return gpu[c];
        const uint32_t leaf = c - (leaves - 1);
        SstNode n{};
        if (leaf >= scene.count) return n;
        const Vpl& v = scene.leaves[leaf];
        n.box_lo = n.box_hi = n.mean = v.position;
        n.colour = v.flux;
        n.intensity = float(ref::sst_intensity(ref_leaves[leaf].flux));
        n.leaf_count = 1;
        n.nu = 1.0f;
        return n;
    };
    double total = 0.0;
    for (uint32_t i = 0; i < scene.count; ++i) total += ref::sst_intensity(ref_leaves[i].flux);
    for (uint32_t i = 0; i + 1 < leaves; ++i) {
        CAPTURE(i);
        const SstNode& n = gpu[i];
        const SstNode l = child(2 * i + 1), r = child(2 * i + 2);
        CHECK(n.leaf_count == l.leaf_count + r.leaf_count);
        if (l.leaf_count == 0 || r.leaf_count == 0) continue;  // a copy of the other child
        const bool inner_children = 2 * i + 2 < leaves - 1;
        if (inner_children) {  // a single float add from the stored children: exact
            CHECK(n.intensity == l.intensity + r.intensity);
            CHECK(n.colour.x == l.colour.x + r.colour.x);
            CHECK(n.colour.y == l.colour.y + r.colour.y);
            CHECK(n.colour.z == l.colour.z + r.colour.z);
        } else {
            CHECK(n.intensity == doctest::Approx(double(l.intensity) + r.intensity).epsilon(1e-6));
        }
        CHECK(n.box_lo.x == std::min(l.box_lo.x, r.box_lo.x));
        CHECK(n.box_lo.y == std::min(l.box_lo.y, r.box_lo.y));
        CHECK(n.box_lo.z == std::min(l.box_lo.z, r.box_lo.z));
        CHECK(n.box_hi.x == std::max(l.box_hi.x, r.box_hi.x));
        CHECK(n.box_hi.y == std::max(l.box_hi.y, r.box_hi.y));
        CHECK(n.box_hi.z == std::max(l.box_hi.z, r.box_hi.z));
        // The mean lies in the box (to the rounding of p1 + b (p2 - p1)); nu never grows going
        // up (the SST paper sec. 3.3).
        const double slack = 1e-6 * 5.0;
        CHECK(n.mean.x >= n.box_lo.x - slack);
        CHECK(n.mean.x <= n.box_hi.x + slack);
        CHECK(n.mean.y >= n.box_lo.y - slack);
        CHECK(n.mean.y <= n.box_hi.y + slack);
        CHECK(n.mean.z >= n.box_lo.z - slack);
        CHECK(n.mean.z <= n.box_hi.z + slack);
        CHECK(n.nu <= std::min(l.nu, r.nu) * (1.0f + 4e-7f));
        CHECK(std::abs(std::sqrt(double(n.normal.x) * n.normal.x + double(n.normal.y) * n.normal.y +
                                 double(n.normal.z) * n.normal.z) -
                       1.0) <= 1e-6);
    }
    CHECK(gpu[0].leaf_count == scene.count);
    CHECK(gpu[0].intensity == doctest::Approx(total).epsilon(1e-5));
}

TEST_CASE("sst: many small workgroups merge across workgroups") {
    // Workgroups of 1 and 32 threads: almost every climb meets a sibling from another workgroup.
    const Scene scene = random_scene({.count = 3000, .seed = 21, .extent = 3.0});
    for (uint32_t size : {1u, 32u}) {
        CAPTURE(size);
        const Comparison c = build_and_compare(scene, {.workgroup_size = size});
        CHECK(c.ambiguous_flags <= c.nodes / 50);
    }
}

TEST_CASE("sst: more than 65,535 workgroups (a grid folded into rows) match the reference") {
    // Workgroups of 1 thread and 150,000 VPLs: 2^17 threads (one per node of the lowest inner level
    // of the 2^18-leaf tree), so 131,072 workgroups, past 65,535 (maxComputeWorkGroupCount's
    // minimum, lavapipe's limit): the generated dispatch folds them into 3 rows of 43,691, one
    // workgroup past the count. Before the fold, add_sst_passes refused this (or the dispatch
    // failed validation).
    // A curved patch (its merged normals stay clear of the reference's decision borders, which
    // uniformly random normals over 150,000 VPLs are not), cut to 150,000 so the tree has padding.
    std::vector<Vpl> vpls = patch(9, 0.01, 2.0, 0.002, 27, {0.3, -0.2, 0.1});
    vpls.resize(150000);
    const Scene scene = padded(std::move(vpls));
    const Comparison c = build_and_compare(scene, {.workgroup_size = 1});
    CHECK(c.nodes == (1u << 18) - 1u);
    CHECK(c.ambiguous_flags <= c.nodes / 50);
}

TEST_CASE("sst: bad arguments are refused with a message") {
    vplkit::Context& ctx = vplkit::test::context();
    auto leaves = vplkit::Buffer::create(ctx, 8 * sizeof(Vpl), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vplkit::MemoryUse::device, "leaves");
    auto nodes = vplkit::Buffer::create(ctx, 7 * sizeof(SstNode), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vplkit::MemoryUse::device, "nodes");
    auto small = vplkit::Buffer::create(ctx, 6 * sizeof(SstNode), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vplkit::MemoryUse::device, "small nodes");
    auto counters = vplkit::Buffer::create(ctx, 3 * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           vplkit::MemoryUse::device, "counters");
    vplkit::PassList passes;
    using vplkit::stages::add_sst_passes;
    CHECK_THROWS_WITH_AS(add_sst_passes(ctx, passes, leaves, nodes, counters, 0), doctest::Contains("no VPLs"),
                         vplkit::Error);
    CHECK_THROWS_WITH_AS(add_sst_passes(ctx, passes, leaves, small, counters, 5), doctest::Contains("small nodes"),
                         vplkit::Error);
    CHECK_THROWS_WITH_AS(add_sst_passes(ctx, passes, leaves, nodes, counters, 9), doctest::Contains("leaves"),
                         vplkit::Error);
    CHECK_THROWS_WITH_AS(add_sst_passes(ctx, passes, leaves, nodes, counters, 5, {.sigma_max = -1.0f}),
                         doctest::Contains("sigma_max"), vplkit::Error);
    CHECK_THROWS_WITH_AS(
        add_sst_passes(ctx, passes, leaves, nodes, counters, 5, {.nu_min = std::numeric_limits<float>::quiet_NaN()}),
        doctest::Contains("finite"), vplkit::Error);
    CHECK_THROWS_WITH_AS(add_sst_passes(ctx, passes, leaves, nodes, counters, 5, {.workgroup_size = 0}),
                         doctest::Contains("workgroup size"), vplkit::Error);
    CHECK(passes.size() == 0);
    add_sst_passes(ctx, passes, leaves, nodes, counters, 5);
    CHECK(passes.size() == 2);
}
