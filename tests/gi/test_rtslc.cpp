// Real-time stochastic lightcuts end to end (add_rtslc_passes on VplTrees built on the GPU): the
// shaders rtslc_cut.comp, rtslc_gi.comp and rtslc_interleave.comp (shaders/gi/) against the double
// reference (tests/reference/rtslc_reference.cpp), on synthetic G-buffers: a floor (y = 0) of
// 16 x 16 pixels with tilted shading normals and varied materials, VPLs on a ceiling, on a wall
// (some grazing), below the floor (behind every pixel), facing away, free, and some of zero flux.
//
// - cuts: equal to the double reference's cut at the GPU's representative pixel, and a partition
//   of the real VPLs, for 1, 2, 64, 65, 100 and 256 VPLs, cut sizes 1, 8 and 64, blocks of 4 and 8;
// - unbiased: with shadow rays off, the mean over 200 seeds at every pixel equals the exact
//   unshadowed sum over all VPLs (double reference) within 5 sigma / sqrt(200), sigma estimated
//   from the samples; interleaved (m = 2) too where each 2 x 2 sub-block is one shading point;
// - interleaving: eq. 3's shares with the per-frame rotation, and the reconstruction's rescale,
//   exactly against the reference where every cut node is a leaf (no randomness);
// - hard cases: a single VPL, 2^k and 2^k + 1 VPLs, coincident VPLs, a pixel on a VPL, HDR flux
//   1e-6..1e6, scenes at 1e-3 and 1e4 scale: finite, nothing dropped, unbiased over seeds;
// - shadows: a VPL behind a wall gives nothing; dead branches return no light and are counted;
// - dispatch splitting and seeds: any slots_per_dispatch gives the same image; bad options.

#include "vplkit/buffer.hpp"
#include "vplkit/bvh_gpu.hpp"
#include "vplkit/context.hpp"
#include "vplkit/error.hpp"
#include "vplkit/gi_counters_buffer.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/rtslc_scratch.hpp"
#include "vplkit/shaders/types.hpp"
#include "vplkit/gbuffer_images.hpp"
#include "vplkit/stages/gi_counters.hpp"
#include "vplkit/stages/rtslc.hpp"
#include "vplkit/vpl_trees.hpp"
#include "vplkit_test/context.hpp"
#include "rtslc_reference.hpp"
#include "synthetic_scene.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace ref = vplkit::reference;
namespace stages = vplkit::stages;
using vplkit::test::d3;
using vplkit::test::half_round;
using vplkit::test::Pixel;
using vplkit::test::shading_point;
using vplkit::test::TestVpl;
using Texel = std::array<float, 4>;

struct Setup {
    uint32_t width = 16, height = 16;
    float scale = 1.0f;
    std::vector<Pixel> pixels;
    std::vector<glm::vec3> triangles;  // three vertices each
    std::vector<TestVpl> vpls;
    glm::vec3 camera{0.0f, 3.0f, 4.0f};
};

// Floor [-3s, 3s]^2 at y = 0 (scene scale 3s), pixels on it.
Setup floor_setup(float s = 1.0f, uint32_t width = 16, uint32_t height = 16) {
    Setup setup;
    setup.width = width;
    setup.height = height;
    setup.scale = s;
    const float f = 3.0f * s;
    setup.triangles = {{-f, 0, -f}, {-f, 0, f}, {f, 0, f}, {-f, 0, -f}, {f, 0, f}, {f, 0, -f}};
    setup.camera = glm::vec3(0.0f, 3.0f, 4.0f) * s;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            Pixel p;
            p.covered = (x * 7 + y * 3) % 13 != 0;
            p.position = glm::vec3(-2.8f + 5.6f * (x + 0.5f) / width, 0.0f, -2.8f + 5.6f * (y + 0.5f) / height) * s;
            p.normal = glm::normalize(glm::vec3(0.6f * (unit(rng) - 0.5f), 1.0f, 0.6f * (unit(rng) - 0.5f)));
            p.roughness = 0.25f + 0.75f * unit(rng);
            p.metallic = unit(rng) < 0.3f ? 1.0f : 0.0f;
            p.albedo = {half_round(unit(rng)), half_round(unit(rng)), half_round(unit(rng))};
            setup.pixels.push_back(p);
        }
    }
    return setup;
}

// `count` VPLs at scale s with flux ~ flux_scale (radiance is scale-invariant for flux ~ s^2):
// cycling through ceiling, wall (the first ones grazing), below the floor, facing away, free,
// and black (zero flux).
std::vector<TestVpl> floor_vpls(uint32_t count, float s, float flux_scale, uint32_t seed = 11) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto colour = [&] {
        return glm::vec3(0.5f + 1.5f * unit(rng), 0.5f + 1.5f * unit(rng), 0.5f + 1.5f * unit(rng)) * flux_scale;
    };
    std::vector<TestVpl> vpls;
    for (uint32_t i = 0; i < count; ++i) {
        switch (i % 10) {
            case 0:
            case 1:
            case 2:
            case 3:  // ceiling, facing down
                vpls.push_back({glm::vec3(-2.5f + 5.0f * unit(rng), 2.0f, -2.5f + 5.0f * unit(rng)) * s,
                                glm::normalize(glm::vec3(0.3f * (unit(rng) - 0.5f), -1.0f, 0.3f * (unit(rng) - 0.5f))),
                                colour()});
                break;
            case 4:
            case 5: {  // wall at x = -2.9 facing +x; low ones light the floor at grazing angles
                const float height = i < 20 ? 0.005f + 0.01f * float(i % 4) : 0.1f + 1.4f * unit(rng);
                vpls.push_back({glm::vec3(-2.9f, height, -2.5f + 5.0f * unit(rng)) * s, {1.0f, 0.0f, 0.0f}, colour()});
                break;
            }
            case 6:  // below the floor, facing up: behind every shading point
                vpls.push_back(
                    {glm::vec3(-2.5f + 5.0f * unit(rng), -0.5f, -2.5f + 5.0f * unit(rng)) * s, {0, 1, 0}, colour()});
                break;
            case 7:  // above the floor, facing up: away from every shading point
                vpls.push_back(
                    {glm::vec3(-2.5f + 5.0f * unit(rng), 1.5f, -2.5f + 5.0f * unit(rng)) * s, {0, 1, 0}, colour()});
                break;
            case 8: {  // free, facing somewhere downwards
                const glm::vec3 n = glm::normalize(glm::vec3(unit(rng) - 0.5f, -0.2f - unit(rng), unit(rng) - 0.5f));
                vpls.push_back(
                    {glm::vec3(-2.5f + 5.0f * unit(rng), 0.1f + 0.8f * unit(rng), -2.5f + 5.0f * unit(rng)) * s, n,
                     colour()});
                break;
            }
            default:  // black: a real leaf that never lights anything
                vpls.push_back({glm::vec3(-2.5f + 5.0f * unit(rng), 1.0f, -2.5f + 5.0f * unit(rng)) * s,
                                {0, -1, 0},
                                glm::vec3(0.0f)});
                break;
        }
    }
    return vpls;
}

Setup standard_setup(uint32_t count = 100, float s = 1.0f, float flux = 1.0f) {
    Setup setup = floor_setup(s);
    setup.vpls = floor_vpls(count, s, flux * s * s);
    return setup;
}

// The GPU side: G-buffer, BVH, VPLs and their trees, built once; render() runs the RTSLC passes.
struct Gpu {
    vplkit::Context& ctx = vplkit::test::context();
    const Setup& setup;
    vplkit::GbufferImages gbuffer;
    vplkit::GpuBvh bvh;
    vplkit::Buffer vpls;
    vplkit::VplTrees trees;
    vplkit::Image indirect;
    vplkit::Buffer counters;
    std::optional<vplkit::RtslcScratch> scratch;

    explicit Gpu(const Setup& s) : setup(s) {
        auto scene = vplkit::test::upload(ctx, setup.width, setup.height, setup.pixels, setup.triangles, setup.vpls);
        gbuffer = std::move(scene.gbuffer);
        bvh = std::move(scene.bvh);
        vpls = std::move(scene.vpls);
        trees = vplkit::VplTrees::create(ctx, uint32_t(setup.vpls.size()));
        vplkit::PassList build("rtslc test trees");
        trees.add_build_passes(build, vpls);
        build.run(ctx);
        indirect = vplkit::Image::create(ctx, setup.width, setup.height, VK_FORMAT_R32G32B32A32_SFLOAT,
                                         VK_IMAGE_USAGE_STORAGE_BIT, "indirect");
        counters = vplkit::create_gi_counters(ctx);
    }

    struct Frame {
        std::vector<Texel> image;
        stages::GiCounts counts;
        std::vector<uint32_t> cuts, representatives;
        size_t passes = 0;
    };

    Frame render(const stages::RtslcOptions& options, bool read_cuts = false) {
        if (!scratch || scratch->cut_size != options.samples_per_pixel || scratch->block_size != options.block_size ||
            scratch->interleave != options.interleave) {
            scratch = vplkit::RtslcScratch::create(ctx, setup.width, setup.height, options);
        }
        vplkit::PassList passes("rtslc test");
        stages::add_rtslc_passes(ctx, passes, gbuffer, bvh, trees, setup.camera, indirect, counters, options, *scratch);
        passes.run(ctx);
        Frame f;
        f.image = indirect.download<Texel>();
        f.counts = vplkit::read_gi_counters(counters);
        f.passes = passes.size();
        if (read_cuts) {
            f.cuts = scratch->cuts.download<uint32_t>(size_t(scratch->block_count()) * scratch->cut_size);
            f.representatives = scratch->representatives.download<uint32_t>(scratch->block_count());
        }
        return f;
    }

    std::vector<ref::RtslcNode> tree() const {
        const auto nodes = trees.light_tree.download<vplkit::shaders::LightTreeNode>(2 * size_t(trees.leaf_count) - 1);
        std::vector<ref::RtslcNode> out;
        for (const auto& n : nodes) {
            out.push_back({{n.box_min.x, n.box_min.y, n.box_min.z},
                           {n.box_max.x, n.box_max.y, n.box_max.z},
                           n.intensity,
                           n.vpl_count});
        }
        return out;
    }
};

double scene_min_distance(const Setup& setup) {
    return ref::kVplMinDistanceFraction * ref::scene_scale(vplkit::test::reference_triangles(setup.triangles));
}

// The exact unshadowed sum at every pixel (0 on background).
std::vector<ref::Vec3> unshadowed(const Setup& setup) {
    const auto vpls = vplkit::test::reference_vpls(setup.vpls);
    const double eps = scene_min_distance(setup);
    std::vector<ref::Vec3> out;
    for (const Pixel& p : setup.pixels) {
        out.push_back(p.covered ? ref::rtslc_unshadowed_sum(shading_point(p), d3(setup.camera), vpls, eps)
                                : ref::Vec3{});
    }
    return out;
}

struct Unbiasedness {
    double largest_z = 0.0;  // over pixels and channels, sigma from the reference's probabilities
    double rms_z = 0.0;
    double largest_sample_z = 0.0;  // the same with sigma estimated from the samples
    double image_z = 0.0;           // of the image's summed radiance, sigma from the samples
    int pixels = 0, exact_pixels = 0;
};

// Per pixel, per tree node: the estimator of one traversal from the node, as moments. S1 = the
// sum of the contributions below (its mean), S2 = E[estimate^2] = sum of f^2 / P(leaf | node),
// from the double reference's child probabilities. `unreachable` is set when a leaf of non-zero
// contribution has probability 0 (a biased estimator).
struct NodeMoments {
    std::vector<std::array<double, 3>> s1, s2;
    bool unreachable = false;
};

NodeMoments node_moments(const Gpu& gpu, const std::vector<ref::RtslcNode>& nodes,
                         const std::vector<vplkit::shaders::Vpl>& leaves, const Pixel& p) {
    const Setup& setup = gpu.setup;
    const double eps = scene_min_distance(setup);
    const uint32_t leaf_count = gpu.trees.leaf_count;
    ref::RtslcShading s;
    s.position = d3(p.position);
    s.normal = d3(p.normal);
    s.wo = d3(glm::normalize(setup.camera - p.position));
    s.base_color = d3(p.albedo);
    s.roughness = p.roughness;
    s.metallic = p.metallic;
    NodeMoments m;
    m.s1.assign(nodes.size(), {0, 0, 0});
    m.s2.assign(nodes.size(), {0, 0, 0});
    for (uint32_t leaf = 0; leaf < gpu.trees.count; ++leaf) {
        const auto& v = leaves[leaf];
        const ref::VplDesc vpl{{v.position.x, v.position.y, v.position.z},
                               {v.normal.x, v.normal.y, v.normal.z},
                               {v.flux.x, v.flux.y, v.flux.z}};
        const auto c = ref::vpl_contribution(shading_point(p), s.wo, vpl, eps);
        for (int k = 0; k < 3; ++k) {
            m.s1[leaf_count - 1 + leaf][k] = c[k];
            m.s2[leaf_count - 1 + leaf][k] = c[k] * c[k];
        }
    }
    for (uint32_t node = leaf_count - 1; node-- > 0;) {
        if (nodes[node].vpl_count == 0) continue;
        const uint32_t l = 2 * node + 1, r = 2 * node + 2;
        const auto choice = ref::rtslc_child_probability(s, nodes[l], nodes[r], eps);
        for (int k = 0; k < 3; ++k) {
            m.s1[node][k] = m.s1[l][k] + m.s1[r][k];
            if (choice.dead) {
                m.unreachable |= m.s1[node][k] != 0.0;
                continue;
            }
            for (auto [child, prob] : {std::pair{l, choice.left}, std::pair{r, 1.0 - choice.left}}) {
                if (prob > 0.0) {
                    m.s2[node][k] += m.s2[child][k] / prob;
                } else {
                    m.unreachable |= m.s1[child][k] != 0.0;
                }
            }
        }
    }
    return m;
}

// The mean over `seeds` frames (seed 1000 + i, frame i) against the exact unshadowed sum over
// every VPL: z = (mean - exact) / (sigma / sqrt(n)). sigma comes from the reference's child
// probabilities at each frame's cuts (the variance of each traversal: S2 - S1^2), because the
// estimator is heavy-tailed: a VPL of probability 1e-4 that holds a tenth of a pixel's light is
// missed by most runs of 100 frames, and the sample sigma of those runs is then ~10x too small
// (seen at 4 x 4 blocks). The sample-sigma z is reported beside it, and gates the image's total
// (a sum over 235 pixels, near-Gaussian). Zero-variance pixels must match to 1e-3 (float BRDF).
Unbiasedness check_unbiased(Gpu& gpu, stages::RtslcOptions options, int seeds, double z_limit) {
    const Setup& setup = gpu.setup;
    const auto exact = unshadowed(setup);
    const auto nodes = gpu.tree();
    const auto leaves = gpu.trees.leaves.download<vplkit::shaders::Vpl>(gpu.trees.leaf_count);
    const size_t n = setup.pixels.size();
    std::vector<NodeMoments> moments(n);
    for (size_t p = 0; p < n; ++p) {
        if (!setup.pixels[p].covered) continue;
        moments[p] = node_moments(gpu, nodes, leaves, setup.pixels[p]);
        CAPTURE(p);
        CHECK_FALSE(moments[p].unreachable);
    }
    std::vector<std::array<double, 3>> sum(n, {0, 0, 0}), sum2(n, {0, 0, 0}), variance(n, {0, 0, 0});
    std::vector<double> image_totals;
    const uint32_t blocks_x = (setup.width + options.block_size - 1) / options.block_size;
    for (int i = 0; i < seeds; ++i) {
        options.seed = uint32_t(1000 + i);
        options.frame = uint32_t(i);
        const auto frame = gpu.render(options, true);
        REQUIRE(frame.counts.cut_short == 0);
        REQUIRE(frame.counts.dropped_samples == 0);
        double total = 0.0;
        for (size_t p = 0; p < n; ++p) {
            REQUIRE(std::isfinite(frame.image[p][0]));
            REQUIRE(std::isfinite(frame.image[p][1]));
            REQUIRE(std::isfinite(frame.image[p][2]));
            REQUIRE(frame.image[p][3] == 0.0f);
            if (!setup.pixels[p].covered) continue;
            const uint32_t x = uint32_t(p) % setup.width, y = uint32_t(p) / setup.width;
            const uint32_t block = (y / options.block_size) * blocks_x + x / options.block_size;
            for (uint32_t slot = 0; slot < options.samples_per_pixel; ++slot) {
                const uint32_t node = frame.cuts[block * options.samples_per_pixel + slot];
                if (node == stages::kRtslcNoNode) break;
                for (int k = 0; k < 3; ++k) {
                    variance[p][k] += moments[p].s2[node][k] - moments[p].s1[node][k] * moments[p].s1[node][k];
                }
            }
            for (int k = 0; k < 3; ++k) {
                sum[p][k] += frame.image[p][k];
                sum2[p][k] += double(frame.image[p][k]) * frame.image[p][k];
                total += frame.image[p][k];
            }
        }
        image_totals.push_back(total);
    }
    Unbiasedness u;
    double z2 = 0.0;
    int zs = 0;
    double exact_total = 0.0;
    for (size_t p = 0; p < n; ++p) {
        if (!setup.pixels[p].covered) continue;
        ++u.pixels;
        bool exact_pixel = true;
        for (int k = 0; k < 3; ++k) {
            exact_total += exact[p][k];
            const double mean = sum[p][k] / seeds;
            const double sample_variance = std::max(0.0, (sum2[p][k] - seeds * mean * mean) / (seeds - 1));
            const double sigma_mean = std::sqrt(std::max(variance[p][k], 0.0)) / seeds;
            CAPTURE(p);
            CAPTURE(k);
            CAPTURE(mean);
            CAPTURE(exact[p][k]);
            CAPTURE(sigma_mean);
            // The reference's variance is 0 up to rounding: the estimate is deterministic here.
            if (sigma_mean <= 1e-6 * std::abs(exact[p][k]) || sigma_mean == 0.0) {
                CHECK(mean == doctest::Approx(exact[p][k]).epsilon(1e-3).scale(1e-30));
                continue;
            }
            exact_pixel = false;
            const double z = (mean - exact[p][k]) / sigma_mean;
            CAPTURE(z);
            CHECK(std::abs(z) < z_limit);
            u.largest_z = std::max(u.largest_z, std::abs(z));
            if (sample_variance > 0.0) {
                u.largest_sample_z =
                    std::max(u.largest_sample_z, std::abs(mean - exact[p][k]) / std::sqrt(sample_variance / seeds));
            }
            z2 += z * z;
            ++zs;
        }
        u.exact_pixels += exact_pixel;
    }
    u.rms_z = zs ? std::sqrt(z2 / zs) : 0.0;
    double mean_total = 0.0, m2 = 0.0;
    for (double t : image_totals) mean_total += t / seeds;
    for (double t : image_totals) m2 += (t - mean_total) * (t - mean_total) / (seeds - 1);
    const double sigma_total = std::sqrt(m2 / seeds);
    if (sigma_total > 1e-6 * std::abs(mean_total)) {
        u.image_z = (mean_total - exact_total) / sigma_total;
        CHECK(std::abs(u.image_z) < z_limit);
    } else {
        CHECK(mean_total == doctest::Approx(exact_total).epsilon(1e-3).scale(1e-30));
    }
    return u;
}

stages::RtslcOptions no_shadows(uint32_t spp = 8, uint32_t block = 8) {
    stages::RtslcOptions o;
    o.samples_per_pixel = spp;
    o.block_size = block;
    o.visibility = false;
    return o;
}

}  // namespace

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

TEST_CASE("rtslc: hard cases stay finite and unbiased") {
    struct Variant {
        std::string name;
        Setup setup;
    };
    std::vector<Variant> variants;
    variants.push_back({"single VPL", standard_setup(1)});
    variants.push_back({"64 VPLs", standard_setup(64)});
    variants.push_back({"65 VPLs", standard_setup(65)});
    {
        // 50 coincident VPLs of one flux: every box is one point, the child probabilities are the
        // intensity ratios, and each traversal's estimate is the exact sum of its node: no variance.
        Setup s = floor_setup();
        for (int i = 0; i < 50; ++i)
            s.vpls.push_back({{0.3f, 1.2f, -0.2f}, glm::normalize(glm::vec3(0.1f, -1, 0)), {1, 2, 3}});
        variants.push_back({"coincident VPLs", s});
    }
    {
        // VPLs exactly on shading points (on their surface, facing up): distance 0.
        Setup s = standard_setup(60);
        for (uint32_t i : {17u, 40u, 101u, 200u}) {
            s.pixels[i].covered = true;
            s.vpls.push_back({s.pixels[i].position, {0, 1, 0}, {2, 2, 2}});
        }
        variants.push_back({"VPLs on shading points", s});
    }
    {
        Setup s = standard_setup(100);
        std::mt19937 rng(9);
        std::uniform_real_distribution<float> decades(-6.0f, 6.0f);
        for (TestVpl& v : s.vpls) v.flux *= std::pow(10.0f, decades(rng));
        variants.push_back({"HDR flux 1e-6..1e6", s});
    }
    variants.push_back({"flux 1e-6", standard_setup(100, 1.0f, 1e-6f)});
    variants.push_back({"flux 1e6", standard_setup(100, 1.0f, 1e6f)});
    variants.push_back({"scale 1e-3", standard_setup(100, 1e-3f)});
    variants.push_back({"scale 1e4", standard_setup(100, 1e4f)});
    for (const Variant& v : variants) {
        CAPTURE(v.name);
        Gpu gpu(v.setup);
        // With shadows: finite and nothing dropped.
        for (uint32_t seed = 0; seed < 4; ++seed) {
            stages::RtslcOptions options;
            options.seed = seed;
            const auto f = gpu.render(options);
            CHECK(f.counts.cut_short == 0);
            CHECK(f.counts.dropped_samples == 0);
            for (const Texel& t : f.image) {
                REQUIRE(std::isfinite(t[0]));
                REQUIRE(std::isfinite(t[1]));
                REQUIRE(std::isfinite(t[2]));
                CHECK(t[3] == 0.0f);
            }
        }
        const auto u = check_unbiased(gpu, no_shadows(8, 8), 64, 5.5);
        MESSAGE(v.name << ": largest |z| " << u.largest_z << ", rms z " << u.rms_z << ", deterministic pixels "
                       << u.exact_pixels << " of " << u.pixels);
        if (v.name == "coincident VPLs" || v.name == "single VPL") {
            CHECK(u.exact_pixels == u.pixels);
        }
    }
}

TEST_CASE("rtslc: a VPL behind a wall gives nothing") {
    // A wall x = 0 (z in [-3, 3], y in [0, 2]) splits the floor; one VPL at x = -1 faces the floor.
    // One VPL: the cut is its leaf, the estimate is exact, so it matches the shadowed reference.
    Setup setup = floor_setup();
    setup.triangles.insert(setup.triangles.end(),
                           {{0, 0, -3}, {0, 2, -3}, {0, 2, 3}, {0, 0, -3}, {0, 2, 3}, {0, 0, 3}});
    setup.vpls = {{{-1.0f, 1.0f, 0.2f}, glm::normalize(glm::vec3(0.3f, -1.0f, 0.0f)), {3, 2, 1}}};
    Gpu gpu(setup);
    const auto triangles = vplkit::test::reference_triangles(setup.triangles);
    const double scale = ref::scene_scale(triangles);
    const auto vpls = vplkit::test::reference_vpls(setup.vpls);
    stages::RtslcOptions options;
    const auto f = gpu.render(options);
    int lit = 0, shadowed = 0;
    for (size_t i = 0; i < setup.pixels.size(); ++i) {
        const Pixel& p = setup.pixels[i];
        if (!p.covered) continue;
        const auto expected = ref::exact_indirect(shading_point(p), d3(setup.camera), vpls, triangles, scale);
        if (expected.near_edge) continue;
        CAPTURE(i);
        if (p.position.x > 0.0f) {
            CHECK(f.image[i] == Texel{0, 0, 0, 0});
            ++shadowed;
        } else {
            lit += f.image[i][0] > 0.0f;
        }
        for (int k = 0; k < 3; ++k) {
            CHECK(double(f.image[i][k]) == doctest::Approx(expected.radiance[k]).epsilon(3e-4).scale(1e-9));
        }
    }
    CHECK(shadowed > 80);
    CHECK(lit > 80);
    // The same VPL without shadow rays lights the far side too.
    const auto unshadowed_frame = gpu.render(no_shadows());
    int far_lit = 0;
    for (size_t i = 0; i < setup.pixels.size(); ++i)
        far_lit += setup.pixels[i].position.x > 0.0f && unshadowed_frame.image[i][0] > 0.0f;
    CHECK(far_lit > 80);
}

TEST_CASE("rtslc: dead branches return no light and are counted") {
    // Every VPL below the floor: each cut node's box lies wholly behind every shading point (whose
    // shading normals are the floor's own here: a tilted one would see some boxes above its plane).
    Setup setup = floor_setup();
    for (Pixel& p : setup.pixels) p.normal = p.geometric;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 40; ++i) {
        setup.vpls.push_back(
            {{-2.5f + 5.0f * unit(rng), -0.2f - unit(rng), -2.5f + 5.0f * unit(rng)}, {0, 1, 0}, {5, 5, 5}});
    }
    Gpu gpu(setup);
    const auto f = gpu.render(no_shadows(8, 8));
    uint32_t covered = 0;
    for (size_t i = 0; i < setup.pixels.size(); ++i) {
        covered += setup.pixels[i].covered;
        CHECK(f.image[i] == Texel{0, 0, 0, 0});
    }
    // 40 VPLs in cuts of 8: every cut node is internal, and dies at its first level.
    CHECK(f.counts.traversals == covered * 8);
    CHECK(f.counts.dead_branches == f.counts.traversals);
    CHECK(f.counts.levels == 0);
    CHECK(f.counts.dropped_samples == 0);
}

TEST_CASE("rtslc: the image does not depend on how the slots are split over dispatches") {
    const Setup setup = standard_setup(100);
    Gpu gpu(setup);
    stages::RtslcOptions options;
    options.samples_per_pixel = 16;
    options.seed = 5;
    const auto whole = gpu.render(options);
    CHECK(whole.passes == 3);  // counters clear, cuts, one gi dispatch
    options.slots_per_dispatch = 3;
    const auto split = gpu.render(options);
    CHECK(split.passes == 2 + 6);
    // Same streams, same additions in slot order: only FMA contraction may differ.
    for (size_t i = 0; i < whole.image.size(); ++i) {
        for (int k = 0; k < 4; ++k) CHECK(split.image[i][k] == doctest::Approx(whole.image[i][k]).epsilon(1e-6));
    }
    CHECK(split.counts.traversals == whole.counts.traversals);
    CHECK(split.counts.levels == whole.counts.levels);
    // The same seed gives the same image; another seed another one.
    options.slots_per_dispatch = 16;
    CHECK(gpu.render(options).image == whole.image);
    options.seed = 6;
    CHECK(gpu.render(options).image != whole.image);
    // Levels per traversal: from cut nodes of ~100 / 16 VPLs, 2-4 levels down.
    CHECK(whole.counts.levels_per_traversal() > 1.0);
    CHECK(whole.counts.levels_per_traversal() < 5.0);
}

TEST_CASE("rtslc: bad options and targets are refused, naming the problem") {
    auto refused = [](auto change, const char* name) {
        stages::RtslcOptions o;
        change(o);
        CAPTURE(name);
        CHECK_THROWS_WITH_AS(stages::validate(o), doctest::Contains(name), vplkit::Error);
    };
    refused([](auto& o) { o.samples_per_pixel = 0; }, "samples_per_pixel");
    refused([](auto& o) { o.samples_per_pixel = 65; }, "samples_per_pixel");
    refused([](auto& o) { o.block_size = 0; }, "block_size");
    refused([](auto& o) { o.block_size = 33; }, "block_size");
    refused([](auto& o) { o.interleave = 3; }, "interleave");
    refused([](auto& o) { o.interleave = 0; }, "interleave");
    refused(
        [](auto& o) {
            o.interleave = 4;
            o.similarity_max_distance = 1.0f;
        },
        "interleave^2");
    refused(
        [](auto& o) {
            o.interleave = 2;
            o.similarity_max_distance = -1.0f;
        },
        "similarity_max_distance");
    // 0 (the default) is the scene-relative distance, with or without interleaving.
    stages::RtslcOptions interleaved;
    interleaved.interleave = 2;
    stages::validate(interleaved);
    refused(
        [](auto& o) {
            o.interleave = 2;
            o.similarity_max_distance = std::numeric_limits<float>::infinity();
        },
        "similarity_max_distance");
    refused([](auto& o) { o.similarity_min_cos = std::numeric_limits<float>::quiet_NaN(); }, "similarity_min_cos");
    refused([](auto& o) { o.slots_per_dispatch = 0; }, "slots_per_dispatch");
    stages::validate({});

    const Setup setup = standard_setup(10);
    Gpu gpu(setup);
    stages::RtslcOptions options;
    auto scratch = vplkit::RtslcScratch::create(gpu.ctx, 16, 16, options);
    auto wrong =
        vplkit::Image::create(gpu.ctx, 16, 15, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT, "small");
    vplkit::PassList passes;
    CHECK_THROWS_WITH_AS(stages::add_rtslc_passes(gpu.ctx, passes, gpu.gbuffer, gpu.bvh, gpu.trees, setup.camera, wrong,
                                                  gpu.counters, options, scratch),
                         doctest::Contains("'small'"), vplkit::Error);
    options.samples_per_pixel = 16;
    CHECK_THROWS_WITH_AS(stages::add_rtslc_passes(gpu.ctx, passes, gpu.gbuffer, gpu.bvh, gpu.trees, setup.camera,
                                                  gpu.indirect, gpu.counters, options, scratch),
                         doctest::Contains("scratch"), vplkit::Error);
    CHECK_THROWS_WITH_AS(vplkit::RtslcScratch::create(gpu.ctx, 0, 16, options), doctest::Contains("0 x 16"),
                         vplkit::Error);
    CHECK(passes.size() == 0);
}

TEST_CASE("rtslc: samples through a non-finite VPL are dropped and counted") {
    // A NaN flux makes its leaf's and every ancestor's intensity NaN: each traversal whose
    // probabilities or VPL it meets is dropped (left out of rgb, counted in alpha and the
    // counters), never silently zeroed, and the rest of the image stays finite.
    Setup setup = standard_setup(60);
    setup.vpls[3].flux.y = std::numeric_limits<float>::quiet_NaN();
    Gpu gpu(setup);
    stages::RtslcOptions options;
    options.seed = 2;
    const auto f = gpu.render(options);
    uint32_t dropped = 0, dropped_pixels = 0;
    for (const Texel& t : f.image) {
        REQUIRE(std::isfinite(t[0]));
        REQUIRE(std::isfinite(t[1]));
        REQUIRE(std::isfinite(t[2]));
        dropped += uint32_t(t[3]);
        dropped_pixels += t[3] > 0.0f;
    }
    CHECK(dropped > 0);
    CHECK(f.counts.dropped_samples == dropped);
    CHECK(f.counts.dropped_pixels == dropped_pixels);
    CHECK(f.counts.cut_short == 0);
}
