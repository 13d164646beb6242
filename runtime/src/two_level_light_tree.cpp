#include "vplkit/two_level_light_tree.hpp"

#include "vplkit/error.hpp"
#include "vplkit/gpu_light_tree.hpp"
#include "vplkit/gpu_lights.hpp"
#include "vplkit/light_power.hpp"
#include "vplkit/stages/light_tree.hpp"

#include <algorithm>
#include <cfloat>
#include <numeric>
#include <string>

namespace vplkit {

namespace {

shaders::LightTreeNode empty_node() {
    shaders::LightTreeNode n{};
    n.box_min = {FLT_MAX, FLT_MAX, FLT_MAX};
    n.box_max = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    return n;
}

// light_tree.glsl's light_tree_merge: left first, so the sums round as the GPU build's.
shaders::LightTreeNode merge(const shaders::LightTreeNode& l, const shaders::LightTreeNode& r) {
    shaders::LightTreeNode n{};
    n.box_min = {std::min(l.box_min.x, r.box_min.x), std::min(l.box_min.y, r.box_min.y),
                 std::min(l.box_min.z, r.box_min.z)};
    n.box_max = {std::max(l.box_max.x, r.box_max.x), std::max(l.box_max.y, r.box_max.y),
                 std::max(l.box_max.z, r.box_max.z)};
    n.intensity = l.intensity + r.intensity;
    n.vpl_count = l.vpl_count + r.vpl_count;
    return n;
}

uint32_t spread_bits(uint32_t v) {  // 10 bits to every third of 30
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
}

// The leaves' order: Morton code of each box centre within the boxes' bounds, ties by index.
std::vector<uint32_t> morton_order(std::span<const shaders::LightTreeNode> leaves) {
    shaders::LightTreeNode all = empty_node();
    for (const auto& n : leaves) all = merge(all, n);
    std::vector<uint32_t> codes(leaves.size());
    for (size_t i = 0; i < leaves.size(); ++i) {
        const float c[3] = {0.5f * (leaves[i].box_min.x + leaves[i].box_max.x),
                            0.5f * (leaves[i].box_min.y + leaves[i].box_max.y),
                            0.5f * (leaves[i].box_min.z + leaves[i].box_max.z)};
        const float lo[3] = {all.box_min.x, all.box_min.y, all.box_min.z};
        const float hi[3] = {all.box_max.x, all.box_max.y, all.box_max.z};
        uint32_t code = 0;
        for (int a = 0; a < 3; ++a) {
            const float extent = hi[a] - lo[a];
            const float t = extent > 0.0f ? (c[a] - lo[a]) / extent : 0.0f;
            code |= spread_bits(uint32_t(std::clamp(t, 0.0f, 1.0f) * 1023.0f)) << a;
        }
        codes[i] = code;
    }
    std::vector<uint32_t> order(leaves.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return codes[a] < codes[b]; });
    return order;
}

// Appends the perfect tree over `leaves` (in leaf order) to `nodes`; returns its root's index.
uint32_t append_tree(std::vector<shaders::LightTreeNode>& nodes, std::span<const shaders::LightTreeNode> leaves) {
    const uint32_t leaf_count = stages::light_tree_leaf_count(uint32_t(leaves.size()));
    const uint32_t base = uint32_t(nodes.size());
    nodes.resize(base + 2 * leaf_count - 1, empty_node());
    for (uint32_t i = 0; i < leaves.size(); ++i) nodes[base + leaf_count - 1 + i] = leaves[i];
    for (uint32_t n = leaf_count - 1; n-- > 0;) {
        nodes[base + n] = merge(nodes[base + 2 * n + 1], nodes[base + 2 * n + 2]);
    }
    return base;
}

shaders::LightTreeNode leaf_node(const TwoLevelLight& light) {
    shaders::LightTreeNode n{};
    n.box_min = light.box_min;
    n.box_max = light.box_max;
    n.intensity = (light.power.x + light.power.y) + light.power.z;  // light_tree_intensity
    n.vpl_count = 1;
    return n;
}

}  // namespace

TwoLevelLightTree build_two_level_light_tree(std::span<const TwoLevelLight> lights,
                                             std::span<const uint32_t> group_first) {
    if (lights.empty()) throw Error("two-level light tree: no lights");
    if (group_first.size() < 2 || group_first.front() != 0 || group_first.back() != lights.size()) {
        throw Error("two-level light tree: the mesh lights do not cover the " + std::to_string(lights.size()) +
                    " lights");
    }
    const uint32_t groups = uint32_t(group_first.size() - 1);
    for (uint32_t g = 0; g < groups; ++g) {
        if (group_first[g + 1] <= group_first[g]) {
            throw Error("two-level light tree: mesh light " + std::to_string(g) + " has no light");
        }
    }
    // Bottom trees first into scratch, then placed after the top tree.
    std::vector<shaders::LightTreeNode> bottom_nodes;
    std::vector<TwoLevelTopLeaf> bottoms(groups);
    std::vector<shaders::LightTreeNode> roots(groups);
    TwoLevelLightTree tree;
    for (uint32_t g = 0; g < groups; ++g) {
        std::vector<shaders::LightTreeNode> leaves;
        for (uint32_t i = group_first[g]; i < group_first[g + 1]; ++i) leaves.push_back(leaf_node(lights[i]));
        const std::vector<uint32_t> order = morton_order(leaves);
        std::vector<shaders::LightTreeNode> sorted;
        TwoLevelTopLeaf& b = bottoms[g];
        b.light_base = uint32_t(tree.leaf_lights.size());
        b.light_count = uint32_t(leaves.size());
        b.leaf_count = stages::light_tree_leaf_count(b.light_count);
        for (uint32_t i : order) {
            sorted.push_back(leaves[i]);
            tree.leaf_lights.push_back(group_first[g] + i);
        }
        b.node_base = append_tree(bottom_nodes, sorted);
        roots[g] = bottom_nodes[b.node_base];
    }
    const std::vector<uint32_t> top_order = morton_order(roots);
    std::vector<shaders::LightTreeNode> top_leaves;
    for (uint32_t g : top_order) top_leaves.push_back(roots[g]);
    append_tree(tree.nodes, top_leaves);
    tree.top_leaf_count = stages::light_tree_leaf_count(groups);
    const uint32_t offset = uint32_t(tree.nodes.size());
    tree.nodes.insert(tree.nodes.end(), bottom_nodes.begin(), bottom_nodes.end());
    for (uint32_t g : top_order) {
        TwoLevelTopLeaf b = bottoms[g];
        b.node_base += offset;
        tree.top_leaves.push_back(b);
    }
    return tree;
}

std::vector<TwoLevelLight> two_level_lights(const scene::Scene& scene, std::vector<uint32_t>& group_first) {
    std::vector<TwoLevelLight> out;
    group_first.assign(1, 0u);
    // Emitters come in ascending triangle order and a primitive instance's triangles are
    // consecutive, so each mesh light's emitters are consecutive too.
    uint32_t primitive = 0;
    bool open = false;
    for (const EmitterTriangle& e : emitter_triangles(scene)) {
        uint32_t p = primitive;
        while (p < scene.primitives.size() &&
               e.scene_triangle >= scene.primitives[p].first_triangle + scene.primitives[p].triangle_count) {
            ++p;
        }
        if (open && p != primitive) group_first.push_back(uint32_t(out.size()));
        primitive = p;
        open = true;
        const shaders::vec3 v[3] = {e.triangle.v0, e.triangle.v1, e.triangle.v2};
        TwoLevelLight light;
        light.box_min = {std::min({v[0].x, v[1].x, v[2].x}), std::min({v[0].y, v[1].y, v[2].y}),
                         std::min({v[0].z, v[1].z, v[2].z})};
        light.box_max = {std::max({v[0].x, v[1].x, v[2].x}), std::max({v[0].y, v[1].y, v[2].y}),
                         std::max({v[0].z, v[1].z, v[2].z})};
        light.power = {float(e.power.x), float(e.power.y), float(e.power.z)};
        out.push_back(light);
    }
    if (open) group_first.push_back(uint32_t(out.size()));
    for (const scene::Light& l : scene.lights) {
        if (l.type == scene::LightType::directional) continue;
        TwoLevelLight light;
        light.box_min = light.box_max = {l.position.x, l.position.y, l.position.z};
        const glm::dvec3 power = punctual_light_power(l, 0.0);
        light.power = {float(power.x), float(power.y), float(power.z)};
        out.push_back(light);
        group_first.push_back(uint32_t(out.size()));
    }
    return out;
}

}  // namespace vplkit
