// The rtslc tests' harness (rtslc_setup.hpp): the floor scene and its VPLs, the GPU side, and the
// unbiasedness check from the double reference's child probabilities.
#include "rtslc_setup.hpp"

#include "vplkit/gi_counters_buffer.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/shaders/types.hpp"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

namespace vplkit::rtslc_test {

Setup floor_setup(float s, uint32_t width, uint32_t height) {
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

std::vector<TestVpl> floor_vpls(uint32_t count, float s, float flux_scale, uint32_t seed) {
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

Setup standard_setup(uint32_t count, float s, float flux) {
    Setup setup = floor_setup(s);
    setup.vpls = floor_vpls(count, s, flux * s * s);
    return setup;
}

Gpu::Gpu(const Setup& s) : setup(s) {
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

Gpu::Frame Gpu::render(const stages::RtslcOptions& options, bool read_cuts) {
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

std::vector<ref::RtslcNode> Gpu::tree() const {
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

double scene_min_distance(const Setup& setup) {
    return ref::kVplMinDistanceFraction * ref::scene_scale(vplkit::test::reference_triangles(setup.triangles));
}

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

namespace {

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

}  // namespace

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

stages::RtslcOptions no_shadows(uint32_t spp, uint32_t block) {
    stages::RtslcOptions o;
    o.samples_per_pixel = spp;
    o.block_size = block;
    o.visibility = false;
    return o;
}

}  // namespace vplkit::rtslc_test
