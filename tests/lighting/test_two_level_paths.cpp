// The two-level traversal's pmf (direct_light_tree.comp's kTwoLevel: rtslc_traverse_in in the top
// tree, then in the chosen top leaf's bottom tree), through a test shader
// (shaders/two_level_paths.comp) that runs 2^16 traversals from the top root at a shading point
// and writes the light reached with the pmf the sampler divides by. Against a double reference
// (tests/reference/rtslc_reference.cpp's child probabilities, the RTSLC paper eqs. 1-2) descending the
// host-built two-level tree (build_two_level_light_tree, the tree the GPU holds):
// - every sample's pmf is the reference probability of the path to its light: relative error at
//   most 2e-4 x sum over the path's choices of 1 / p_choice + 1e-6 (the per-choice float error
//   tests/gi/test_rtslc_probabilities.cpp bounds, 2e-4 absolute, carried through the product);
// - the reference pmfs (and dead-branch mass) over all lights sum to 1: per node the two children's
//   probabilities sum to 1, through both levels;
// - the pmfs the GPU reports over the distinct lights it reached sum to 1 less the reference mass
//   of the lights it never reached, within 1e-3;
// - the frequencies follow the pmfs: chi-square over the lights expected >= 5 times (the rest
//   pooled) below dof + 5 sqrt(2 dof), a 5 sigma normal bound.

#include "vplkit/buffer.hpp"
#include "vplkit/context.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/gpu_two_level_light_tree.hpp"
#include "vplkit/lighting_test/two_level_paths.hpp"
#include "vplkit/pass_list.hpp"
#include "vplkit/two_level_light_tree.hpp"
#include "vplkit_test/context.hpp"
#include "rtslc_reference.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

#include "direct_light_tree_fixture.hpp"

using namespace direct_tree_fixture;

namespace {

namespace ref = vplkit::reference;
namespace shader = vplkit::lighting_test::two_level_paths;
using Result = vplkit::lighting_test::TwoLevelPathResult;

constexpr uint32_t kSamples = 1u << 16;
constexpr double kMinDistance = 0.01;

ref::RtslcNode ref_node(const vplkit::shaders::LightTreeNode& n) {
    return {{n.box_min.x, n.box_min.y, n.box_min.z}, {n.box_max.x, n.box_max.y, n.box_max.z}, n.intensity, n.vpl_count};
}

// The reference pmf of every light (by index into the tree's lights) and, per light, the sum of
// 1 / p over its path's choices (the pmf's error bound); `dead` collects the dead branches' mass.
struct ReferencePmf {
    std::vector<double> pmf, inverse_sum;
    double dead = 0.0;
};

void descend(const vplkit::TwoLevelLightTree& tree, const ref::RtslcShading& s, uint32_t base, uint32_t node,
             uint32_t leaf_count, double probability, double inverse_sum,
             const std::function<void(uint32_t, double, double)>& at_leaf, ReferencePmf& out) {
    if (node >= leaf_count - 1) {
        at_leaf(node + 1 - leaf_count, probability, inverse_sum);
        return;
    }
    const uint32_t left = 2 * node + 1;
    const auto p = ref::rtslc_child_probability(s, ref_node(tree.nodes[base + left]),
                                                ref_node(tree.nodes[base + left + 1]), kMinDistance);
    if (p.dead) {
        out.dead += probability;
        return;
    }
    if (p.left > 0.0) {
        descend(tree, s, base, left, leaf_count, probability * p.left, inverse_sum + 1.0 / p.left, at_leaf, out);
    }
    if (p.left < 1.0) {
        descend(tree, s, base, left + 1, leaf_count, probability * (1.0 - p.left), inverse_sum + 1.0 / (1.0 - p.left),
                at_leaf, out);
    }
}

ReferencePmf reference_pmf(const vplkit::TwoLevelLightTree& tree, uint32_t light_count, const ref::RtslcShading& s) {
    ReferencePmf out;
    out.pmf.assign(light_count, 0.0);
    out.inverse_sum.assign(light_count, 0.0);
    descend(
        tree, s, 0, 0, tree.top_leaf_count, 1.0, 0.0,
        [&](uint32_t top_leaf, double p_top, double inv_top) {
            const auto& bottom = tree.top_leaves.at(top_leaf);
            descend(
                tree, s, bottom.node_base, 0, bottom.leaf_count, p_top, inv_top,
                [&](uint32_t leaf, double p, double inv) {
                    REQUIRE(leaf < bottom.light_count);
                    const uint32_t light = tree.leaf_lights[bottom.light_base + leaf];
                    out.pmf[light] += p;
                    out.inverse_sum[light] = inv;
                },
                out);
        },
        out);
    return out;
}

}  // namespace

TEST_CASE("two-level traversal: the pmf is the probability of the path taken, and the frequencies follow it") {
    SceneBuilder b;
    {
        // Mesh lights of 1, 2, 3, 6, 9 and 17 triangles and two point lights, radiance 1e-2..1e3.
        Lcg rng{41u};
        const std::vector<uint32_t> sizes = {1, 2, 3, 6, 9, 17};
        for (size_t g = 0; g < sizes.size(); ++g) {
            b.begin_mesh_light();
            const float power = std::pow(10.0f, -2.0f + 5.0f * rng.next());
            const uint32_t material =
                b.add_emissive(glm::vec3(0.4f + rng.next(), 0.5f, 0.3f + rng.next()) * power, g % 3 == 2);
            const glm::vec3 c{-1.5f + 3.0f * rng.next(), 0.5f + 1.4f * rng.next(), -1.5f + 3.0f * rng.next()};
            const float radius = 0.05f + 0.45f * rng.next();
            for (uint32_t t = 0; t < sizes[g]; ++t) {
                const glm::vec3 p = c + radius * glm::vec3(2.0f * rng.next() - 1.0f, 0.0f, 2.0f * rng.next() - 1.0f);
                add_small_emitter(b, p, radius * (0.05f + 0.3f * rng.next()), true, material);
            }
        }
        vplkit::scene::Light point;
        point.position = {0.6f, 1.3f, -0.4f};
        point.intensity = 2.0f;
        vplkit::scene::Light second = point;
        second.position = {-1.2f, 0.8f, 1.1f};
        second.intensity = 30.0f;
        b.s.lights = {point, second};
    }
    std::vector<uint32_t> group_first;
    const auto lights = vplkit::two_level_lights(b.s, group_first);
    const auto tree = vplkit::build_two_level_light_tree(lights, group_first);
    const uint32_t light_count = uint32_t(lights.size());
    REQUIRE(light_count == 38 + 2);

    auto& ctx = vplkit::test::context();
    const auto emitters = vplkit::upload_emitters(ctx, b.s);
    const auto gpu_tree = vplkit::GpuTwoLevelLightTree::create(ctx, b.s, emitters);
    const auto buffers = gpu_tree.buffers();
    auto output = vplkit::Buffer::create(ctx, kSamples * sizeof(Result), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         vplkit::MemoryUse::device, "two-level paths");
    const auto& pipeline = ctx.pipeline<shader::Pipeline>();

    struct Point {
        glm::vec3 position, normal;
    };
    for (const Point& x : {Point{{0.1f, 0.0f, 0.2f}, {0, 1, 0}}, Point{{-1.6f, 0.0f, 1.5f}, {0, 1, 0}},
                           Point{{1.2f, 1.0f, -0.3f}, glm::normalize(glm::vec3(-1, 0.3f, 0.2f))}}) {
        CAPTURE(x.position.x);
        const glm::vec3 wo = glm::normalize(kCamera - x.position);
        vplkit::PassList passes("two-level paths test");
        passes.add("two-level paths",
                   {vplkit::Use::read(buffers.nodes), vplkit::Use::read(buffers.bottoms),
                    vplkit::Use::read(buffers.leaf_lights), vplkit::Use::write(output)},
                   [&](VkCommandBuffer cmd) {
                       shader::Bindings bind;
                       bind.light_tree = buffers.nodes.descriptor();
                       bind.bottoms = buffers.bottoms.descriptor();
                       bind.leaf_lights = buffers.leaf_lights.descriptor();
                       bind.results = output.descriptor();
                       shader::Push push{};
                       push.position = {x.position.x, x.position.y, x.position.z};
                       push.normal = {x.normal.x, x.normal.y, x.normal.z};
                       push.wo = {wo.x, wo.y, wo.z};
                       push.base_color = {float(kAlbedo[0]), float(kAlbedo[1]), float(kAlbedo[2])};
                       push.roughness = float(kRoughness);
                       push.metallic = 0.0f;
                       push.min_distance2 = float(kMinDistance * kMinDistance);
                       push.count = kSamples;
                       push.top_leaf_count = tree.top_leaf_count;
                       push.seed = 1234u;
                       pipeline.dispatch(cmd, bind, push, kSamples);
                   });
        passes.run(ctx);
        const auto results = output.download<Result>(kSamples);

        ref::RtslcShading s;
        s.position = {x.position.x, x.position.y, x.position.z};
        s.normal = {x.normal.x, x.normal.y, x.normal.z};
        s.wo = {wo.x, wo.y, wo.z};
        s.base_color = kAlbedo;
        s.roughness = kRoughness;
        s.metallic = 0.0;
        const ReferencePmf expected = reference_pmf(tree, light_count, s);
        double total = expected.dead;
        for (double p : expected.pmf) total += p;
        CHECK(total == doctest::Approx(1.0).epsilon(1e-12));

        std::vector<uint32_t> counts(light_count + 1, 0);  // the last: dead branches
        std::map<uint32_t, double> reported;               // light -> the pmf the GPU gave it
        uint32_t dead = 0;
        for (const Result& r : results) {
            if (r.light == ~0u) {
                REQUIRE(r.status == 1u);  // kRtslcDeadBranch: never a traversal cut short
                ++dead;
                ++counts[light_count];
                continue;
            }
            REQUIRE(r.light < light_count);
            ++counts[r.light];
            REQUIRE(std::isfinite(r.pmf));
            const double p = expected.pmf[r.light];
            REQUIRE(p > 0.0);  // the GPU never reaches a light the reference gives 0
            CHECK(std::abs(r.pmf - p) <= (2e-4 * expected.inverse_sum[r.light] + 1e-6) * p);
            reported[r.light] = r.pmf;
        }
        CHECK(double(dead) <= expected.dead * kSamples + 5.0 * std::sqrt(expected.dead * kSamples) + 1.0);
        double reported_sum = 0.0, unreached = 0.0;
        for (uint32_t l = 0; l < light_count; ++l) {
            if (reported.count(l)) {
                reported_sum += reported[l];
            } else {
                unreached += expected.pmf[l];
            }
        }
        CHECK(std::abs(reported_sum - (1.0 - expected.dead - unreached)) <= 1e-3);

        double chi2 = 0.0, pooled_expected = 0.0, pooled_count = 0.0;
        int bins = 0;
        for (uint32_t l = 0; l <= light_count; ++l) {
            const double e = (l < light_count ? expected.pmf[l] : expected.dead) * kSamples;
            if (e >= 5.0) {
                chi2 += (counts[l] - e) * (counts[l] - e) / e;
                ++bins;
            } else {
                pooled_expected += e;
                pooled_count += counts[l];
            }
        }
        if (pooled_expected >= 5.0) {
            chi2 += (pooled_count - pooled_expected) * (pooled_count - pooled_expected) / pooled_expected;
            ++bins;
        }
        const int dof = bins - 1;
        REQUIRE(dof >= 5);
        MESSAGE("chi-square " << chi2 << " over " << dof << " dof; " << reported.size() << " lights reached");
        CHECK(chi2 <= dof + 5.0 * std::sqrt(2.0 * dof));
    }
}
