#version 460
#extension GL_GOOGLE_include_directive : require
// The leaf level of the light tree over a scene's lights (direct light through the tree,
// stages/scene_light_tree.hpp): as light_tree_leaves.comp for VPLs, one node per leaf of the
// sorted, power-of-two padded order, but a leaf's box is its light's extent rather than a point.
// An emissive triangle's box holds its three corners: the receiver's cosine bound of a node
// (gi_box_cosine_bound) is then 0 only where every point of every triangle below lies behind the
// shading point; a centroid box could lie behind while a corner is in front, and a weight of 0
// there would lose that light (bias). A point or spot light's box is its position.
//
// Orientation (a triangle's normal and sidedness, a spot's cone) is not in the node: the RTSLC paper
// sec. 4 leaves bounding cones out of the perfect tree's 32-byte node ("only subtle loss of
// sampling quality") and so does the kit; the sample's evaluation applies them. The weights
// therefore overestimate lights that face away, which costs variance, never bias.
//
// intensity: light_tree_intensity of the light's RGB power (the proxies' flux), as a VPL's.

#include "vplkit/vpl.glsl"
#include "vplkit/emitters.glsl"
#include "vplkit/lights.glsl"
#include "vplkit/light_tree.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

// Per light: position (triangle centroid or light position), normal, flux = RGB power.
layout(std430, set = 0, binding = 0) readonly buffer LightProxyBuffer { Vpl items[]; } proxies;
// The key sort's values: leaf i holds light order[i].
layout(std430, set = 0, binding = 1) readonly buffer SortValueBuffer { uint items[]; } order;
layout(std430, set = 0, binding = 2) readonly buffer EmissiveTriangleBuffer { EmissiveTriangle items[]; } emitters;
layout(std430, set = 0, binding = 3) readonly buffer PunctualLightBuffer { PunctualLight items[]; } lights;
layout(std430, set = 0, binding = 4) writeonly buffer LightTreeNodeBuffer { LightTreeNode items[]; } nodes;

layout(push_constant) uniform LightTreeSceneLeavesPush {
    uint count;           // real lights
    uint leaf_count;      // count rounded up to a power of two
    uint triangle_count;  // lights [0, triangle_count) are emitters; the rest lights[i - triangle_count]
} push;

void main() {
    uint leaf = linear_thread_index();
    if (leaf >= push.leaf_count) {
        return;
    }
    LightTreeNode node = light_tree_empty_node();
    if (leaf < push.count) {
        uint light = order.items[leaf];
        float intensity = light_tree_intensity(proxies.items[light].flux);
        if (light < push.triangle_count) {
            EmissiveTriangle e = emitters.items[light];
            node = LightTreeNode(min(min(e.v0, e.v1), e.v2), intensity, max(max(e.v0, e.v1), e.v2), 1u);
        } else {
            vec3 p = lights.items[light - push.triangle_count].position;
            node = LightTreeNode(p, intensity, p, 1u);
        }
    }
    nodes.items[light_tree_leaf_node(push.leaf_count, leaf)] = node;
}
