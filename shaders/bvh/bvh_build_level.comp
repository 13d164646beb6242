#version 460
#extension GL_GOOGLE_include_directive : require
// GPU BVH build, step 7, and of a refit (see vplkit/bvh_build.glsl): the boxes and output
// subtree sizes of the interior nodes at one depth, from their children's (one dispatch per
// depth, deepest first). Level by level rather than Karras 2012's bottom-up walk with atomic
// counters, which needs buffer memory barriers in divergent flow (dropped threads on lavapipe).

#include "vplkit/bvh_build.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) buffer BvhBuildNodeBuffer { BvhBuildNode items[]; } nodes;
layout(std430, set = 0, binding = 1) buffer BvhBuildLinkBuffer { BvhBuildLink items[]; } links;
// Each slot's depth when it is an interior node, else kBvhBuildNone (bvh_build_depths.comp).
layout(std430, set = 0, binding = 2) readonly buffer BvhBuildLevelBuffer { uint items[]; } levels;

layout(push_constant) uniform BvhBuildLevelPush {
    uint internal_count;  // triangle count - 1: only internal slots can be interior nodes
    uint depth;
} push;

void main() {
    uint slot = linear_thread_index();
    if (slot >= push.internal_count || levels.items[slot] != push.depth) {
        return;
    }
    BvhBuildNode node = nodes.items[slot];
    BvhBuildNode left = nodes.items[node.left];
    BvhBuildNode right = nodes.items[node.right];
    nodes.items[slot].lo = min(left.lo, right.lo);
    nodes.items[slot].hi = max(left.hi, right.hi);
    links.items[slot].size = 1u + links.items[node.left].size + links.items[node.right].size;
}
