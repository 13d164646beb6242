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
    uvec2 nodes_address;  // with kBvhBuildAddressed (bvh_build.glsl)
    uvec2 links_address;
} push;

BVH_BUILD_GETTER(BvhBuildLink, links, BvhBuildLinkArray)
BVH_BUILD_GETTER(BvhBuildNode, nodes, BvhBuildNodeArray)

void main() {
    uint slot = linear_thread_index();
    if (slot >= push.internal_count || levels.items[slot] != push.depth) {
        return;
    }
    BvhBuildNode node = nodes_get(slot);
    BvhBuildNode left = nodes_get(node.left);
    BvhBuildNode right = nodes_get(node.right);
    vec3 lo = min(left.lo, right.lo);
    vec3 hi = max(left.hi, right.hi);
    BVH_BUILD_SET(nodes, BvhBuildNodeArray, slot, .lo, lo);
    BVH_BUILD_SET(nodes, BvhBuildNodeArray, slot, .hi, hi);
    uint size = 1u + links_get(node.left).size + links_get(node.right).size;
    BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .size, size);
}
