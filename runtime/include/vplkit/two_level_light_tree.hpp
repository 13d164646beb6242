#pragma once
// The two-level light tree over a scene's lights (the RTSLC paper sec. 3.1): one bottom-level perfect
// tree per mesh light (the emissive triangles of one primitive instance; a point or spot light is
// a mesh light of one leaf), and a top-level perfect tree over the mesh lights whose leaf i
// carries bottom tree i's root (box, intensity) and says where that tree lives.
//
// Built on the host: a bottom tree depends only on its mesh's triangles, so it is rebuilt only
// when they change, while the top tree (a few nodes per mesh light) is what moving instances
// rebuild. Layout, all in one LightTreeNode array (vplkit/light_tree.glsl's heap order in each
// tree): the top tree's light_tree_node_count(mesh lights) nodes first, then every bottom tree.
// A sampler selects its cut in the top tree, descends it to a top leaf, then continues in that
// leaf's bottom tree to a light; the light's pmf is the product of every choice on the way.
//
// Uploaded by vplkit/gpu_two_level_light_tree.hpp and sampled by direct_light_tree.comp
// (kTwoLevel): `vplkit render --direct tree2`.

#include "vplkit/scene.hpp"
#include "vplkit/shaders/types.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace vplkit {

// One light as the trees see it: its extent (a triangle's corners' box, a punctual light's
// position) and its RGB power (watts), whose light_tree_intensity is the leaf's intensity.
struct TwoLevelLight {
    shaders::vec3 box_min{};
    shaders::vec3 box_max{};
    shaders::vec3 power{};
};

// Where top leaf i's bottom tree lives: the struct the shaders read (vplkit/two_level_light_tree.glsl).
using TwoLevelTopLeaf = shaders::LightTreeBottom;

struct TwoLevelLightTree {
    uint32_t top_leaf_count = 0;  // light_tree_leaf_count(mesh lights)
    std::vector<shaders::LightTreeNode> nodes;
    std::vector<TwoLevelTopLeaf> top_leaves;  // one per real top leaf, in top leaf order
    std::vector<uint32_t> leaf_lights;        // light indices into the `lights` the tree was built over
};

// The tree over `lights`, grouped into mesh lights: mesh light g holds lights
// [group_first[g], group_first[g + 1]) (group_first ascending, starting at 0, the last entry
// lights.size()). Within a mesh light and among mesh lights, leaves are ordered by the Morton code
// of their box centre (as the one-level tree's keys). Throws vplkit::Error for no lights, an empty
// group or groups that do not cover the lights.
TwoLevelLightTree build_two_level_light_tree(std::span<const TwoLevelLight> lights,
                                             std::span<const uint32_t> group_first);

// The lights of `scene` in light_tree_lights' order (emissive triangles, then point and spot
// lights) and their mesh lights: one per primitive instance with emitting triangles, then one per
// punctual light. Returns group_first through `group_first`.
std::vector<TwoLevelLight> two_level_lights(const scene::Scene& scene, std::vector<uint32_t>& group_first);

}  // namespace vplkit
