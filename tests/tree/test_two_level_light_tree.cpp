// The two-level light tree's host build (runtime/src/two_level_light_tree.cpp) on irregular mesh
// lights (1, 3, 8, 37 and 200 lights, powers from 1e-4 to 1e4), checked independently of how it
// was built: every light is in exactly one bottom tree's leaves, every inner node of either level
// is the merge of its children, a top leaf carries its bottom tree's root bit for bit, and, for
// the sampler the layout serves (descend the top tree to a top leaf, then its bottom tree to a
// light, each child chosen with probability I w / (I_l w_l + I_r w_r)), the child probabilities
// of every node sum to 1 and the product-of-choices pmf over all lights sums to 1 with no light
// of nonzero weight at pmf 0 (so sum f / pmf x pmf is the exact sum: unbiased).

#include "vplkit/error.hpp"
#include "vplkit/scene.hpp"
#include "vplkit/two_level_light_tree.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

namespace {

using vplkit::TwoLevelLight;
using vplkit::TwoLevelLightTree;
using vplkit::shaders::LightTreeNode;

bool same(const LightTreeNode& a, const LightTreeNode& b) {
    return a.box_min.x == b.box_min.x && a.box_min.y == b.box_min.y && a.box_min.z == b.box_min.z &&
           a.box_max.x == b.box_max.x && a.box_max.y == b.box_max.y && a.box_max.z == b.box_max.z &&
           a.intensity == b.intensity && a.vpl_count == b.vpl_count;
}

// Checks tree [base, base + 2 * leaf_count - 1): inner nodes merge their children (left first).
void check_tree(const std::vector<LightTreeNode>& nodes, uint32_t base, uint32_t leaf_count) {
    for (uint32_t n = 0; n + 1 < leaf_count; ++n) {
        const LightTreeNode& l = nodes[base + 2 * n + 1];
        const LightTreeNode& r = nodes[base + 2 * n + 2];
        const LightTreeNode& p = nodes[base + n];
        CHECK(p.intensity == l.intensity + r.intensity);
        CHECK(p.vpl_count == l.vpl_count + r.vpl_count);
        CHECK(p.box_min.x == std::min(l.box_min.x, r.box_min.x));
        CHECK(p.box_max.y == std::max(l.box_max.y, r.box_max.y));
    }
}

// A child's weight at x: intensity over the squared distance to the box (clamped), 0 for bogus.
double weight(const LightTreeNode& n, const double x[3]) {
    if (n.vpl_count == 0) return 0.0;
    const double lo[3] = {n.box_min.x, n.box_min.y, n.box_min.z}, hi[3] = {n.box_max.x, n.box_max.y, n.box_max.z};
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) {
        const double d = std::max({lo[a] - x[a], 0.0, x[a] - hi[a]});
        d2 += d * d;
    }
    return double(n.intensity) / std::max(d2, 1e-4);
}

// Adds pmf x (the path so far) to pmf[light] for every light below node `n` of the tree at `base`.
void descend(const TwoLevelLightTree& t, uint32_t base, uint32_t leaf_count, uint32_t n, double p, const double x[3],
             const std::function<void(uint32_t leaf, double p)>& at_leaf) {
    if (n >= leaf_count - 1) {
        at_leaf(n - (leaf_count - 1), p);
        return;
    }
    const double wl = weight(t.nodes[base + 2 * n + 1], x), wr = weight(t.nodes[base + 2 * n + 2], x);
    if (!(wl + wr > 0.0)) return;  // a dead branch: no light
    const double pl = wl / (wl + wr), pr = wr / (wl + wr);
    CHECK(pl + pr == doctest::Approx(1.0).epsilon(1e-12));
    if (pl > 0.0) descend(t, base, leaf_count, 2 * n + 1, p * pl, x, at_leaf);
    if (pr > 0.0) descend(t, base, leaf_count, 2 * n + 2, p * pr, x, at_leaf);
}

}  // namespace

TEST_CASE("two-level light tree over irregular mesh lights: structure and path pmf") {
    const std::vector<uint32_t> sizes = {1, 3, 8, 37, 200};
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<TwoLevelLight> lights;
    std::vector<uint32_t> group_first = {0};
    for (size_t g = 0; g < sizes.size(); ++g) {
        const float cx = 3.0f * float(g);
        for (uint32_t i = 0; i < sizes[g]; ++i) {
            TwoLevelLight l;
            l.box_min = {cx + u(rng), 2.0f + u(rng), u(rng)};
            l.box_max = {l.box_min.x + 0.1f * u(rng), l.box_min.y, l.box_min.z + 0.1f * u(rng)};
            const float power = std::pow(10.0f, -4.0f + 8.0f * u(rng));  // 1e-4 .. 1e4
            l.power = {power, 0.5f * power, 0.25f * power};
            lights.push_back(l);
        }
        group_first.push_back(uint32_t(lights.size()));
    }
    const TwoLevelLightTree t = vplkit::build_two_level_light_tree(lights, group_first);

    REQUIRE(t.top_leaves.size() == sizes.size());
    CHECK(t.top_leaf_count == 8);
    check_tree(t.nodes, 0, t.top_leaf_count);
    std::vector<uint32_t> seen(lights.size(), 0);
    for (uint32_t i = 0; i < t.top_leaves.size(); ++i) {
        const auto& b = t.top_leaves[i];
        CHECK(same(t.nodes[t.top_leaf_count - 1 + i], t.nodes[b.node_base]));
        CHECK(b.leaf_count >= b.light_count);
        CHECK(b.leaf_count < 2 * b.light_count);
        check_tree(t.nodes, b.node_base, b.leaf_count);
        for (uint32_t j = 0; j < b.light_count; ++j) ++seen[t.leaf_lights[b.light_base + j]];
        for (uint32_t j = b.light_count; j < b.leaf_count; ++j) {
            CHECK(t.nodes[b.node_base + b.leaf_count - 1 + j].vpl_count == 0);  // bogus padding
        }
    }
    for (uint32_t i = t.top_leaves.size(); i < t.top_leaf_count; ++i) {
        CHECK(t.nodes[t.top_leaf_count - 1 + i].vpl_count == 0);
    }
    CHECK(std::all_of(seen.begin(), seen.end(), [](uint32_t c) { return c == 1; }));
    CHECK(t.nodes[0].vpl_count == lights.size());

    // Path pmf: top tree to a top leaf, then its bottom tree to a light, at a few shading points.
    for (const double x0 : {-1.0, 5.0, 13.0}) {
        const double x[3] = {x0, 0.0, 0.5};
        std::vector<double> pmf(lights.size(), 0.0);
        descend(t, 0, t.top_leaf_count, 0, 1.0, x, [&](uint32_t top_leaf, double p_top) {
            REQUIRE(top_leaf < t.top_leaves.size());
            const auto& b = t.top_leaves[top_leaf];
            descend(t, b.node_base, b.leaf_count, 0, p_top, x, [&](uint32_t leaf, double p) {
                REQUIRE(leaf < b.light_count);
                pmf[t.leaf_lights[b.light_base + leaf]] += p;
            });
        });
        double total = 0.0;
        for (uint32_t i = 0; i < lights.size(); ++i) {
            total += pmf[i];
            CHECK(pmf[i] > 0.0);  // every light here has weight > 0: none may be unreachable
        }
        CHECK(total == doctest::Approx(1.0).epsilon(1e-9));
    }
}

TEST_CASE("two-level light tree: mesh lights of a scene are its emitting primitive instances, then punctual lights") {
    vplkit::scene::Scene s;
    s.source = "two-level test";
    s.materials.resize(2);
    s.materials[1].emissive_factor = {1.0f, 1.0f, 1.0f};
    // Primitives: 2 dark triangles, 1 emissive, 3 emissive, 5 emissive.
    const std::vector<std::pair<uint32_t, uint32_t>> prims = {{2, 0}, {1, 1}, {3, 1}, {5, 1}};
    for (const auto& [count, material] : prims) {
        vplkit::scene::PrimitiveInstance p;
        p.first_triangle = uint32_t(s.triangle_materials.size());
        p.triangle_count = count;
        p.material = material;
        for (uint32_t i = 0; i < count; ++i) {
            const uint32_t t = uint32_t(s.triangle_materials.size());
            for (glm::vec3 v : {glm::vec3(float(t), 1, 0), glm::vec3(float(t) + 1, 1, 0), glm::vec3(float(t), 1, 1)}) {
                vplkit::scene::Vertex vertex;
                vertex.position = v;
                s.indices.push_back(uint32_t(s.vertices.size()));
                s.vertices.push_back(vertex);
            }
            if (material == 1) s.emissive_triangles.push_back(t);
            s.triangle_materials.push_back(material);
        }
        s.primitives.push_back(p);
    }
    vplkit::scene::Light point;
    point.position = {0, 3, 0};
    s.lights.push_back(point);
    std::vector<uint32_t> group_first;
    const auto lights = vplkit::two_level_lights(s, group_first);
    CHECK(lights.size() == 10);
    CHECK(group_first == std::vector<uint32_t>{0, 1, 4, 9, 10});
    const TwoLevelLightTree t = vplkit::build_two_level_light_tree(lights, group_first);
    CHECK(t.top_leaves.size() == 4);

    CHECK_THROWS_AS(vplkit::build_two_level_light_tree(lights, std::vector<uint32_t>{0, 4, 4, 10}), vplkit::Error);
    CHECK_THROWS_AS(vplkit::build_two_level_light_tree(lights, std::vector<uint32_t>{0, 9}), vplkit::Error);
}
