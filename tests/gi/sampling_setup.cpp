#include "sampling_setup.hpp"

#include "vplkit/context.hpp"
#include "vplkit/gi_counters_buffer.hpp"
#include "vplkit/hybrid_cuts.hpp"
#include "vplkit/image.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/rtslc_scratch.hpp"
#include "vplkit/vpl_trees.hpp"
#include "vplkit_test/context.hpp"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace vplkit::sampling_test {

using test::d3;
using test::half_round;

Scene room(uint32_t width, uint32_t height, uint32_t vpl_count, float s, float flux_scale) {
    Scene scene;
    scene.width = width;
    scene.height = height;
    scene.scale = s;
    const float f = 3.0f * s;
    // Floor, and a double-sided occluding quad at y = s over part of it.
    scene.triangles = {{-f, 0, -f},
                       {-f, 0, f},
                       {f, 0, f},
                       {-f, 0, -f},
                       {f, 0, f},
                       {f, 0, -f},
                       {-0.5f * s, s, -0.5f * s},
                       {-0.5f * s, s, 0.7f * s},
                       {0.6f * s, s, 0.7f * s},
                       {-0.5f * s, s, -0.5f * s},
                       {0.6f * s, s, 0.7f * s},
                       {0.6f * s, s, -0.5f * s}};
    scene.camera = glm::vec3(0.0f, 3.0f, 4.0f) * s;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            Pixel p;
            p.covered = (x * 7 + y * 3) % 23 != 0;
            p.position = glm::vec3(-2.8f + 5.6f * (x + 0.5f) / width, 0.0f, -2.8f + 5.6f * (y + 0.5f) / height) * s;
            p.normal = glm::normalize(glm::vec3(0.2f * (unit(rng) - 0.5f), 1.0f, 0.2f * (unit(rng) - 0.5f)));
            p.roughness = 0.4f + 0.6f * unit(rng);
            p.metallic = unit(rng) < 0.2f ? 1.0f : 0.0f;
            p.albedo = {half_round(0.2f + 0.8f * unit(rng)), half_round(0.2f + 0.8f * unit(rng)),
                        half_round(0.2f + 0.8f * unit(rng))};
            scene.pixels.push_back(p);
        }
    }
    auto colour = [&] {
        return glm::vec3(0.5f + unit(rng), 0.5f + unit(rng), 0.5f + unit(rng)) * flux_scale / float(vpl_count);
    };
    for (uint32_t i = 0; i < vpl_count; ++i) {
        const uint32_t kind = i % 10;
        TestVpl v;
        if (kind < 5) {  // ceiling, facing down: coplanar clusters the SST can substitute
            v = {glm::vec3(-2.5f + 5.0f * unit(rng), 2.0f, -2.5f + 5.0f * unit(rng)) * s, {0, -1, 0}, colour()};
        } else if (kind < 8) {  // wall at x = -2.9 facing +x
            v = {glm::vec3(-2.9f, 0.05f + 1.8f * unit(rng), -2.5f + 5.0f * unit(rng)) * s, {1, 0, 0}, colour()};
        } else if (kind == 8) {  // free, facing somewhere downwards
            const glm::vec3 n = glm::normalize(glm::vec3(unit(rng) - 0.5f, -0.2f - unit(rng), unit(rng) - 0.5f));
            v = {glm::vec3(-2.5f + 5.0f * unit(rng), 0.2f + 0.6f * unit(rng), -2.5f + 5.0f * unit(rng)) * s, n,
                 colour()};
        } else {  // below the floor facing up: behind every shading point
            v = {glm::vec3(-2.5f + 5.0f * unit(rng), -0.5f, -2.5f + 5.0f * unit(rng)) * s, {0, 1, 0}, colour()};
        }
        scene.vpls.push_back(v);
    }
    return scene;
}

Scene glossy_room(uint32_t width, uint32_t height, uint32_t vpl_count) {
    Scene scene = room(width, height, vpl_count);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (size_t i = 0; i < scene.pixels.size(); ++i) {
        Pixel& p = scene.pixels[i];
        const size_t row = i / width;
        p.roughness = row == 0 ? 0.05f : row == 1 ? 1.0f : 0.05f + 0.95f * unit(rng);
        p.metallic = i % 3 == 0 ? 1.0f : 0.0f;
    }
    return scene;
}

Rendered render(const Scene& scene, const RunOptions& options) {
    Context& ctx = test::context();
    const uint32_t capacity = options.gpu_count_capacity;
    std::vector<test::TestVpl> uploaded = scene.vpls;
    std::mt19937 garbage_rng(99);
    std::uniform_real_distribution<float> garbage(-5.0f, 5.0f);
    while (uploaded.size() < capacity) {  // bright, finite junk: it must not reach the trees
        const glm::vec3 p{garbage(garbage_rng), garbage(garbage_rng), garbage(garbage_rng)};
        uploaded.push_back({p, glm::normalize(p + glm::vec3(0.0f, 6.0f, 0.0f)), glm::vec3(100.0f)});
    }
    auto [gbuffer, bvh, vpls] = test::upload(ctx, scene.width, scene.height, scene.pixels, scene.triangles, uploaded);
    vplkit::VplTreeOptions tree_options;
    tree_options.sst = options.sst;
    auto trees = vplkit::VplTrees::create(ctx, capacity > 0 ? capacity : uint32_t(scene.vpls.size()), tree_options);
    auto indirect = Image::create(ctx, scene.width, scene.height, VK_FORMAT_R32G32B32A32_SFLOAT,
                                  VK_IMAGE_USAGE_STORAGE_BIT, "indirect");
    auto counters = vplkit::create_gi_counters(ctx);

    PassList passes("sampling test");
    Buffer count_words;
    if (capacity > 0) {
        std::vector<uint32_t> words(options.gpu_count_word + 1, 12345u);
        words.back() = options.gpu_count >= 0 ? uint32_t(options.gpu_count) : uint32_t(scene.vpls.size());
        count_words = Buffer::create(ctx, words.size() * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                     MemoryUse::device, "vpl count");
        count_words.upload(words);
        trees.add_build_passes(passes, vpls,
                               stages::ElementCount::on_gpu(count_words, options.gpu_count_word, capacity));
    } else {
        trees.add_build_passes(passes, vpls);
    }
    Rendered out;
    if (options.method == Method::sst) {
        stages::SstGiOptions o;
        o.samples_per_pixel = options.samples_per_pixel;
        o.seed = options.seed;
        o.visibility = options.visibility;
        o.glossy = options.glossy;
        stages::add_sst_gi_pass(ctx, passes, gbuffer, bvh, trees, scene.camera, indirect, counters, o);
        passes.run(ctx);
    } else if (options.method == Method::rtslc) {
        stages::RtslcOptions o;
        o.samples_per_pixel = options.samples_per_pixel;
        o.block_size = options.block_size;
        o.seed = options.seed;
        o.frame = options.seed;
        o.visibility = options.visibility;
        o.glossy = options.glossy;
        o.glossy_lobe_mis = options.rtslc_lobe_mis;
        auto scratch = vplkit::RtslcScratch::create(ctx, scene.width, scene.height, o);
        stages::add_rtslc_passes(ctx, passes, gbuffer, bvh, trees, scene.camera, indirect, counters, o, scratch);
        passes.run(ctx);
    } else {
        stages::HybridOptions o;
        o.samples_per_pixel = options.samples_per_pixel;
        o.block_size = options.block_size;
        o.seed = options.seed;
        o.visibility = options.visibility;
        o.similarity_max_distance = options.similarity_max_distance * scene.scale;
        o.mock_cuts = options.mock_cuts;
        o.traversal = options.traversal;
        o.glossy = options.glossy;
        auto cuts = vplkit::HybridCuts::create(ctx, scene.width, scene.height, o);
        stages::add_hybrid_gi_passes(ctx, passes, gbuffer, bvh, trees, scene.camera, indirect, counters, cuts, o);
        passes.run(ctx);
        out.cuts = cuts.cuts.download<uint32_t>(cuts.cuts.size() / sizeof(uint32_t));
        out.blocks = cuts.blocks.download<shaders::HybridBlock>(cuts.blocks.size() / sizeof(shaders::HybridBlock));
    }
    out.image = indirect.download<Texel>();
    out.counts = vplkit::read_gi_counters(counters);
    out.sst = trees.sst.download<shaders::SstNode>(stages::sst_node_count(trees.count));
    out.leaves = trees.leaves.download<shaders::Vpl>(trees.leaf_count);
    out.leaf_count = trees.leaf_count;
    return out;
}

std::vector<reference::Vec3> exact(const Scene& scene, bool visibility) {
    const auto triangles = reference_triangles(scene.triangles);
    const auto vpls = reference_vpls(scene.vpls);
    const double scale = reference::scene_scale(triangles);
    std::vector<reference::Vec3> out;
    for (const Pixel& p : scene.pixels) {
        if (!p.covered) {
            out.push_back({0, 0, 0});
            continue;
        }
        const auto sum = reference::exact_indirect(
            shading_point(p), d3(scene.camera), vpls,
            visibility ? std::span<const reference::Triangle>(triangles) : std::span<const reference::Triangle>(),
            scale);
        out.push_back(sum.radiance);
    }
    return out;
}

std::vector<MeanCheck> check_means(const Scene& scene, RunOptions options, const std::vector<uint32_t>& seed_counts,
                                   const std::vector<reference::Vec3>& truth) {
    const size_t n = scene.pixels.size();
    std::vector<std::array<double, 3>> sum(n), sum2(n);
    std::vector<MeanCheck> checks;
    const uint32_t seeds = seed_counts.empty() ? 0 : seed_counts.back();
    for (uint32_t s = 0; s < seeds; ++s) {
        options.seed = 1000 + s;
        const Rendered r = render(scene, options);
        REQUIRE(r.counts.dropped_samples == 0);
        REQUIRE(r.counts.cut_short == 0);
        for (size_t i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c) {
                sum[i][c] += r.image[i][c];
                sum2[i][c] += double(r.image[i][c]) * r.image[i][c];
            }
        }
        if (std::find(seed_counts.begin(), seed_counts.end(), s + 1) == seed_counts.end()) continue;
        const uint32_t count = s + 1;
        MeanCheck check;
        check.seeds = count;
        for (size_t i = 0; i < n; ++i) {
            if (!scene.pixels[i].covered) continue;
            for (int c = 0; c < 3; ++c) {
                const double mean = sum[i][c] / count;
                const double var = std::max(sum2[i][c] / count - mean * mean, 0.0) * count / (count - 1);
                // The float evaluation's own error (~1e-5 relative) bounds how small sigma may be.
                const double sigma = std::sqrt(var / count) + 1e-5 * std::abs(truth[i][c]) + 1e-12;
                const double z = std::abs(mean - truth[i][c]) / sigma;
                ++check.checked;
                check.worst_z = std::max(check.worst_z, z);
                if (z > 4.5) {
                    ++check.outside;
                    MESSAGE(count << " seeds, pixel " << i << " channel " << c << ": mean " << mean << " exact "
                                  << truth[i][c] << " sigma " << sigma);
                }
            }
        }
        checks.push_back(check);
    }
    return checks;
}

MeanCheck check_mean(const Scene& scene, RunOptions options, uint32_t seeds,
                     const std::vector<reference::Vec3>& truth) {
    return check_means(scene, options, {seeds}, truth).front();
}

double relative_rmse(const Scene& scene, const std::vector<Texel>& image, const std::vector<reference::Vec3>& truth) {
    double err = 0.0, norm = 0.0;
    for (size_t i = 0; i < scene.pixels.size(); ++i) {
        if (!scene.pixels[i].covered) continue;
        for (int c = 0; c < 3; ++c) {
            const double d = image[i][c] - truth[i][c];
            err += d * d;
            norm += truth[i][c] * truth[i][c];
        }
    }
    return std::sqrt(err / norm);
}

}  // namespace vplkit::sampling_test
