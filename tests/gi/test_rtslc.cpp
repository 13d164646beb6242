// Real-time stochastic lightcuts end to end (add_rtslc_passes on VplTrees built on the GPU): the
// shaders rtslc_cut.comp, rtslc_gi.comp and rtslc_interleave.comp (shaders/gi/) against the double
// reference (tests/reference/rtslc_reference.cpp), on the synthetic floor of rtslc_setup.hpp.
//
// - cuts: equal to the double reference's cut at the GPU's representative pixel, and a partition
//   of the real VPLs, for 1, 2, 64, 65, 100 and 256 VPLs, cut sizes 1, 8 and 64, blocks of 4 and 8;
// - unbiased: with shadow rays off, the mean over 200 seeds at every pixel equals the exact
//   unshadowed sum over all VPLs (double reference) within 5 sigma / sqrt(200), sigma estimated
//   from the samples; interleaved (m = 2) too where each 2 x 2 sub-block is one shading point;
// - interleaving: eq. 3's shares with the per-frame rotation, and the reconstruction's rescale,
//   exactly against the reference where every cut node is a leaf (no randomness).
// Hard cases, shadows, dispatch splitting and bad options: test_rtslc_hard_cases.cpp.
#include "vplkit/shaders/types.hpp"
#include "rtslc_setup.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

using namespace vplkit::rtslc_test;

TEST_CASE("rtslc: cuts equal the reference cut and partition the real VPLs") {
    int compared = 0, close_calls = 0;
    for (uint32_t count : {1u, 2u, 64u, 65u, 100u, 256u}) {
        Setup setup = standard_setup(count);
        // The top-right 8 x 8 block has no surface: its cut must be empty.
        for (uint32_t y = 0; y < 8; ++y) {
            for (uint32_t x = 8; x < 16; ++x) setup.pixels[y * 16 + x].covered = false;
        }
        Gpu gpu(setup);
        const auto nodes = gpu.tree();
        const double eps = scene_min_distance(setup);
        for (uint32_t spp : {1u, 8u, 64u}) {
            for (uint32_t block : {4u, 8u}) {
                CAPTURE(count);
                CAPTURE(spp);
                CAPTURE(block);
                auto options = no_shadows(spp, block);
                options.seed = count * 7 + spp;
                const auto frame = gpu.render(options, true);
                CHECK(frame.counts.cut_short == 0);
                const uint32_t blocks_x = 16 / block;
                for (uint32_t b = 0; b < blocks_x * blocks_x; ++b) {
                    CAPTURE(b);
                    const uint32_t bx = b % blocks_x, by = b / blocks_x;
                    bool any_covered = false;
                    for (uint32_t y = by * block; y < (by + 1) * block; ++y) {
                        for (uint32_t x = bx * block; x < (bx + 1) * block; ++x)
                            any_covered |= setup.pixels[y * 16 + x].covered;
                    }
                    const uint32_t rep = frame.representatives[b];
                    std::vector<uint32_t> cut;
                    for (uint32_t i = 0; i < spp; ++i) {
                        const uint32_t node = frame.cuts[b * spp + i];
                        if (node == stages::kRtslcNoNode) {
                            // Packed: no node after the first empty slot.
                            for (uint32_t j = i; j < spp; ++j) CHECK(frame.cuts[b * spp + j] == stages::kRtslcNoNode);
                            break;
                        }
                        cut.push_back(node);
                    }
                    if (!any_covered) {
                        CHECK(rep == stages::kRtslcNoNode);
                        CHECK(cut.empty());
                        continue;
                    }
                    REQUIRE(rep != stages::kRtslcNoNode);
                    const uint32_t rx = rep % 16, ry = rep / 16;
                    CHECK(rx / block == bx);
                    CHECK(ry / block == by);
                    REQUIRE(setup.pixels[rep].covered);
                    // Every real VPL under exactly one cut node.
                    std::vector<int> seen(count, 0);
                    for (uint32_t node : cut) {
                        REQUIRE(node < nodes.size());
                        CHECK(nodes[node].vpl_count > 0);
                        for (uint32_t leaf : ref::rtslc_leaves_below(nodes, gpu.trees.leaf_count, node)) {
                            REQUIRE(leaf < count);
                            ++seen[leaf];
                        }
                    }
                    for (uint32_t leaf = 0; leaf < count; ++leaf) CHECK(seen[leaf] == 1);
                    CHECK(cut.size() == std::min<size_t>(spp, count));
                    // The reference's cut at the same representative pixel.
                    const Pixel& p = setup.pixels[rep];
                    ref::RtslcShading s;
                    s.position = d3(p.position);
                    s.normal = d3(p.normal);
                    s.wo = d3(glm::normalize(setup.camera - p.position));
                    s.base_color = d3(p.albedo);
                    s.roughness = p.roughness;
                    s.metallic = p.metallic;
                    const auto expected = ref::rtslc_select_cut(nodes, gpu.trees.leaf_count, s, eps, spp);
                    // An exact tie (0) goes to the smaller node index on both sides; a near tie may
                    // go either way in float.
                    if (expected.closest_call > 0.0 && expected.closest_call < 1e-4) {
                        ++close_calls;
                        continue;
                    }
                    ++compared;
                    CHECK(std::multiset<uint32_t>(cut.begin(), cut.end()) ==
                          std::multiset<uint32_t>(expected.nodes.begin(), expected.nodes.end()));
                }
            }
        }
    }
    MESSAGE("blocks compared with the reference cut: " << compared << ", near ties skipped: " << close_calls);
    CHECK(close_calls * 20 <= compared);
}

TEST_CASE("rtslc: unbiased over 200 seeds without shadows") {
    const Setup setup = standard_setup(100);
    Gpu gpu(setup);
    const auto u = check_unbiased(gpu, no_shadows(8, 8), 200, 5.0);
    MESSAGE("pixels " << u.pixels << " (deterministic " << u.exact_pixels << "), largest |z| " << u.largest_z
                      << ", rms z " << u.rms_z << ", image z " << u.image_z << ", largest |z| with the sample sigma "
                      << u.largest_sample_z);
    CHECK(u.pixels - u.exact_pixels > u.pixels / 2);  // most pixels are really sampled
    // At 200 frames the sample sigma gives the same verdict here (it may not for fewer frames).
    CHECK(u.largest_sample_z < 5.0);
    CHECK(u.rms_z < 1.5);  // z ~ N(0, 1): a biased estimator drifts far above
    // A cut per 4 x 4 block and a single-node cut: unbiased as well.
    const auto small_blocks = check_unbiased(gpu, no_shadows(4, 4), 100, 5.0);
    const auto one_node = check_unbiased(gpu, no_shadows(1, 8), 100, 5.0);
    MESSAGE("4 x 4 blocks, 4 spp: largest |z| " << small_blocks.largest_z << ", rms z " << small_blocks.rms_z
                                                << "; 1 spp: largest |z| " << one_node.largest_z << ", rms z "
                                                << one_node.rms_z);
}

TEST_CASE("rtslc: interleaved sampling is unbiased where a sub-block is one shading point") {
    // Each 2 x 2 sub-block holds four copies of one shading point: the four shares of the cut
    // together are one unbiased estimate of its light, and the reconstruction sums them.
    Setup setup = standard_setup(100);
    for (uint32_t y = 0; y < 16; ++y) {
        for (uint32_t x = 0; x < 16; ++x) setup.pixels[y * 16 + x] = setup.pixels[(y & ~1u) * 16 + (x & ~1u)];
    }
    Gpu gpu(setup);
    auto options = no_shadows(8, 8);
    options.interleave = 2;
    options.similarity_max_distance = 0.01f;
    const auto u = check_unbiased(gpu, options, 200, 5.0);
    MESSAGE("interleave 2: largest |z| " << u.largest_z << ", rms z " << u.rms_z << ", image z " << u.image_z);
    CHECK(u.rms_z < 1.5);
}

TEST_CASE("rtslc: interleaved shares rotate per frame and the reconstruction rescales them") {
    // 8 VPLs and 8 nodes per cut: every cut node is a leaf, so a pixel's estimate over its share
    // is exact, and the shares and the rescale can be checked against eq. 3 directly.
    Setup setup = standard_setup(8);
    Gpu gpu(setup);
    const auto leaves = gpu.trees.leaves.download<vplkit::shaders::Vpl>(gpu.trees.leaf_count);
    const double eps = scene_min_distance(setup);
    auto leaf_light = [&](const Pixel& p, uint32_t node) {
        const auto& v = leaves[node - (gpu.trees.leaf_count - 1)];
        const ref::VplDesc vpl{{v.position.x, v.position.y, v.position.z},
                               {v.normal.x, v.normal.y, v.normal.z},
                               {v.flux.x, v.flux.y, v.flux.z}};
        const ref::Vec3 wo = d3(glm::normalize(setup.camera - p.position));
        return ref::vpl_contribution(shading_point(p), wo, vpl, eps);
    };
    for (uint32_t m : {2u}) {
        for (uint32_t frame = 0; frame < 5; ++frame) {
            for (float max_distance : {1e-6f, 100.0f}) {
                CAPTURE(frame);
                CAPTURE(max_distance);
                auto options = no_shadows(8, 8);
                options.interleave = m;
                options.frame = frame;
                options.similarity_min_cos = -1.0f;
                options.similarity_max_distance = max_distance;  // 1e-6: only the pixel itself
                const auto f = gpu.render(options, true);
                uint32_t traversals = 0;
                for (uint32_t y = 0; y < 16; ++y) {
                    for (uint32_t x = 0; x < 16; ++x) {
                        const Pixel& p = setup.pixels[y * 16 + x];
                        if (!p.covered) continue;
                        const uint32_t b = (y / 8) * 2 + x / 8;
                        const uint32_t* cut = &f.cuts[b * 8];
                        // eq. 3 with p = (i + f) mod m^2, over the pixel's similar sub-block pixels.
                        ref::Vec3 sum{};
                        uint32_t covered_nodes = 0;
                        for (uint32_t yy = y - y % m; yy < y - y % m + m; ++yy) {
                            for (uint32_t xx = x - x % m; xx < x - x % m + m; ++xx) {
                                const Pixel& q = setup.pixels[yy * 16 + xx];
                                if (!q.covered) continue;
                                if ((xx != x || yy != y) && max_distance < 1.0f) continue;
                                const uint32_t i = (yy % m) * m + xx % m;
                                const uint32_t share = (i + frame) % (m * m);
                                const uint32_t first = share * 8 / (m * m), end = (share + 1) * 8 / (m * m);
                                covered_nodes += end - first;
                                for (uint32_t slot = first; slot < end; ++slot) {
                                    const auto c = leaf_light(q, cut[slot]);
                                    for (int k = 0; k < 3; ++k) sum[k] += c[k];
                                }
                            }
                        }
                        traversals += 8 / (m * m);
                        CAPTURE(x);
                        CAPTURE(y);
                        for (int k = 0; k < 3; ++k) {
                            const double expected = sum[k] * 8.0 / covered_nodes;
                            CHECK(double(f.image[y * 16 + x][k]) ==
                                  doctest::Approx(expected).epsilon(1e-3).scale(1e-6));
                        }
                    }
                }
                CHECK(f.counts.traversals == traversals);
                CHECK(f.counts.levels == 0);  // cut nodes are leaves
                CHECK(f.passes == 4);         // counters clear, cuts, gi, interleave
            }
        }
    }
}
