#version 460
#extension GL_GOOGLE_include_directive : require
// The leaf level of the perfect light tree (the RTSLC paper sec. 3.1): one node per leaf of the sorted,
// power-of-two padded leaf array. A leaf is bogus by its index (>= count), never by its data, so
// whatever a bogus slot holds it becomes the empty node.

#include "vplkit/vpl.glsl"
#include "vplkit/light_tree.glsl"
#include "vplkit/dispatch.glsl"
#include "vplkit/element_count.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer LeafBuffer { Vpl items[]; } leaves;
layout(std430, set = 0, binding = 1) writeonly buffer LightTreeNodeBuffer { LightTreeNode items[]; } nodes;
VPLKIT_DECLARE_ELEMENT_COUNT(2)

layout(push_constant) uniform LightTreeLeavesPush {
    uint count;       // real VPLs, or the capacity when count_word names the GPU's count
    uint leaf_count;  // count rounded up to a power of two
    uint count_word;  // element_count.glsl
} push;

void main() {
    uint leaf = linear_thread_index();
    if (leaf >= push.leaf_count) {
        return;
    }
    LightTreeNode node = light_tree_empty_node();
    if (leaf < element_count(push.count, push.count_word)) {
        Vpl vpl = leaves.items[leaf];
        node = LightTreeNode(vpl.position, light_tree_intensity(vpl.flux), vpl.position, 1u);
    }
    nodes.items[light_tree_leaf_node(push.leaf_count, leaf)] = node;
}
