#version 460
#extension GL_GOOGLE_include_directive : require
// Test-only: rtslc_child_probability and rtslc_node_bound (vplkit/rtslc.glsl) on a list of
// node pairs and shading points, so the host can check them against the double reference and
// check that the two children's probabilities sum to one.

#include "vplkit/brdf.glsl"
#include "vplkit/light_tree.glsl"
#include "vplkit/gi_bounds.glsl"
#include "vplkit/rtslc.glsl"

layout(local_size_x = 64) in;

struct RtslcProbabilityCase {
    LightTreeNode left;
    LightTreeNode right;
    vec3 position;
    float roughness;
    vec3 normal;
    float metallic;
    vec3 wo;
    float min_distance2;
    vec3 base_color;
    uint unused;
};

struct RtslcProbabilityResult {
    float p_left;       // rtslc_choice_probability(left, true)
    float p_right;      // rtslc_choice_probability(left, false)
    uint dead;          // 1 for a dead branch
    float bound_left;   // rtslc_node_bound of the left child
    float bound_right;
    uint unused0, unused1, unused2;
};

layout(std430, set = 0, binding = 0) readonly buffer RtslcProbabilityCaseBuffer { RtslcProbabilityCase items[]; } cases;
layout(std430, set = 0, binding = 1) writeonly buffer RtslcProbabilityResultBuffer { RtslcProbabilityResult items[]; } results;

layout(push_constant) uniform RtslcProbabilitiesPush {
    uint count;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) {
        return;
    }
    RtslcProbabilityCase c = cases.items[i];
    RtslcShading s = RtslcShading(c.position, c.normal, c.wo, c.base_color, c.roughness, c.metallic);
    RtslcChildProbability p = rtslc_child_probability(s, c.left, c.right, c.min_distance2);
    RtslcProbabilityResult r;
    r.p_left = rtslc_choice_probability(p.left, true);
    r.p_right = rtslc_choice_probability(p.left, false);
    r.dead = p.dead ? 1u : 0u;
    r.bound_left = rtslc_node_bound(s, c.left, c.min_distance2);
    r.bound_right = rtslc_node_bound(s, c.right, c.min_distance2);
    r.unused0 = 0u;
    r.unused1 = 0u;
    r.unused2 = 0u;
    results.items[i] = r;
}
