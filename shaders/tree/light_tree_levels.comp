#version 460
#extension GL_GOOGLE_include_directive : require
// One group of internal levels of the perfect light tree (the RTSLC paper sec. 4): the `levels` levels
// above `source_level`, all in this one dispatch. A node `depth` levels above the source level
// reads its 2^depth descendants there directly, so no node of the group waits for another; the
// host puts a barrier between groups only.

#include "vplkit/light_tree.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

// Most levels one group may build: a top node of the group reads 2^8 = 256 source nodes.
const uint kLightTreeMaxGroupLevels = 8u;

layout(std430, set = 0, binding = 0) buffer LightTreeNodeBuffer { LightTreeNode items[]; } nodes;

layout(push_constant) uniform LightTreeLevelsPush {
    uint source_level;  // complete already; root level 0
    uint levels;        // destination levels source_level - levels .. source_level - 1, 1..8
} push;

void main() {
    // The destination levels are consecutive in heap order: nodes [2^top - 1, 2^source - 1).
    uint top_level = push.source_level - push.levels;
    uint node = light_tree_level_start(top_level) + linear_thread_index();
    if (node >= light_tree_level_start(push.source_level)) {
        return;
    }
    uint depth = push.source_level - light_tree_level(node);
    uint first = light_tree_first_descendant(node, depth);
    uint span = 1u << depth;

    // The intensity is summed pairwise in tree order with a stack of partial sums (the binary
    // counter of i), so it rounds exactly as a level-by-level build would: the tree does not
    // depend on the group size, and every parent's intensity is the float sum of its children's.
    // Boxes and counts are exact in any order.
    float partial[kLightTreeMaxGroupLevels + 1u];
    uint top = 0u;
    vec3 box_min = vec3(kLightTreeFloatMax);
    vec3 box_max = vec3(-kLightTreeFloatMax);
    uint vpl_count = 0u;
    for (uint i = 0u; i < span; ++i) {
        LightTreeNode source = nodes.items[first + i];
        box_min = min(box_min, source.box_min);
        box_max = max(box_max, source.box_max);
        vpl_count += source.vpl_count;
        float sum = source.intensity;
        for (uint pairs = i; (pairs & 1u) != 0u; pairs >>= 1) {
            --top;
            sum = partial[top] + sum;
        }
        partial[top] = sum;
        ++top;
    }
    nodes.items[node] = LightTreeNode(box_min, partial[0], box_max, vpl_count);
}
