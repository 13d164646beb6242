#version 460
#extension GL_GOOGLE_include_directive : require
// Test-only: one invocation = one two-level traversal at a fixed shading point, as
// direct_light_tree.comp's kTwoLevel does it (rtslc_traverse_in in the top tree from its root to a
// top leaf, then in that leaf's bottom tree to a light), writing the light reached and the pmf the
// sampler divides by, so the host can check that pmf against the probability of the path taken
// (a double reference) and the frequencies against the pmfs.

#include "vplkit/rng.glsl"
#define VPLKIT_LIGHT_TREE_BINDING 0
#include "vplkit/rtslc_tree_sampling.glsl"
#include "vplkit/two_level_light_tree.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 1) readonly buffer LightTreeBottomBuffer { LightTreeBottom items[]; } bottoms;
layout(std430, set = 0, binding = 2) readonly buffer LeafLightBuffer { uint items[]; } leaf_lights;

struct TwoLevelPathResult {
    uint light;  // leaf_lights' entry reached; ~0u when a traversal did not reach a leaf
    float pmf;   // the product of both traversals' path probabilities
    uint levels; // levels descended in both trees
    uint status; // the first traversal's status that was not kRtslcReachedLeaf, else kRtslcReachedLeaf
};
layout(std430, set = 0, binding = 3) writeonly buffer TwoLevelPathResultBuffer { TwoLevelPathResult items[]; } results;

layout(push_constant) uniform TwoLevelPathsPush {
    vec3 position;
    uint count;
    vec3 normal;
    uint top_leaf_count;
    vec3 wo;
    float min_distance2;
    vec3 base_color;
    float roughness;
    float metallic;
    uint seed;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) {
        return;
    }
    RtslcShading s = RtslcShading(push.position, push.normal, push.wo, push.base_color, push.roughness, push.metallic);
    Rng rng = rng_create(push.seed, i);
    TwoLevelPathResult r = TwoLevelPathResult(~0u, 0.0, 0u, kRtslcReachedLeaf);
    RtslcTraversal t = rtslc_traverse_in(s, 0u, 0u, push.top_leaf_count, push.min_distance2, rng);
    r.levels = t.levels;
    r.status = t.status;
    if (t.status == kRtslcReachedLeaf) {
        LightTreeBottom bottom = bottoms.items[light_tree_node_leaf(push.top_leaf_count, t.node)];
        RtslcTraversal b = rtslc_traverse_in(s, bottom.node_base, 0u, bottom.leaf_count, push.min_distance2, rng);
        r.levels += b.levels;
        r.status = b.status;
        if (b.status == kRtslcReachedLeaf) {
            r.light = leaf_lights.items[bottom.light_base + light_tree_node_leaf(bottom.leaf_count, b.node)];
            r.pmf = t.path_probability * b.path_probability;
        }
    }
    results.items[i] = r;
}
