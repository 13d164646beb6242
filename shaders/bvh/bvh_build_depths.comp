#version 460
#extension GL_GOOGLE_include_directive : require
// GPU BVH build, step 5 (see vplkit/bvh_build.glsl): each slot's depth, by walking up its parent
// pointers (no thread waits for another, unlike a bottom-up pass with atomics), and its kind in
// the output tree (and, for the box passes, its level word); the tree's depths and leaf counts into the info buffer (reduced per
// workgroup in shared memory, then one set of atomics).

#include "vplkit/bvh_build.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) buffer BvhBuildLinkBuffer { BvhBuildLink items[]; } links;
layout(std430, set = 0, binding = 1) buffer BvhBuildInfoBuffer { BvhBuildInfo value; } info;
// The keys buffer, free once the hierarchy is built: each slot's depth when it is an interior
// node, else kBvhBuildNone, so that the per-depth box passes read 4 bytes a slot, not a link.
layout(std430, set = 0, binding = 2) writeonly buffer BvhBuildLevelBuffer { uint items[]; } levels;

layout(push_constant) uniform BvhBuildDepthsPush {
    uint triangle_count;
    uint max_leaf_triangles;
    uint max_depth;
    uvec2 links_address;  // with kBvhBuildAddressed (bvh_build.glsl)
} push;

BVH_BUILD_GETTER(BvhBuildLink, links, BvhBuildLinkArray)

shared uint shared_lbvh_depth;
shared uint shared_depth;
shared uint shared_leaves;
shared uint shared_largest;
shared uint shared_capped;

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        shared_lbvh_depth = 0u;
        shared_depth = 0u;
        shared_leaves = 0u;
        shared_largest = 0u;
        shared_capped = 0u;
    }
    barrier();

    uint slot = linear_thread_index();
    uint n = push.triangle_count;
    if (slot < 2u * n - 1u) {
        uint depth = 0u;
        uint node = slot;
        uint parent = links_get(slot).parent;
        while (parent != kBvhBuildNone && depth < kBvhBuildMaxWalk) {
            node = parent;
            parent = links_get(node).parent;
            ++depth;
        }
        uint count = links_get(slot).count;
        uint above = links_get(slot).parent;
        uint above_count = above == kBvhBuildNone ? 0xffffffffu : links_get(above).count;
        bool kept = depth <= push.max_depth && above_count > push.max_leaf_triangles;
        bool leaf = kept && (count <= push.max_leaf_triangles || depth == push.max_depth);
        BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .depth, depth);
        BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .kind, leaf ? kBvhBuildLeaf : (kept ? kBvhBuildInterior : kBvhBuildHidden));
        levels.items[slot] = kept && !leaf ? depth : kBvhBuildNone;
        if (slot >= n - 1u) {
            atomicMax(shared_lbvh_depth, depth);
        }
        if (leaf) {
            atomicMax(shared_depth, depth);
            atomicAdd(shared_leaves, 1u);
            atomicMax(shared_largest, count);
            if (count > push.max_leaf_triangles) {
                atomicAdd(shared_capped, 1u);
            }
        }
    }
    barrier();

    if (gl_LocalInvocationIndex == 0u) {
        atomicMax(info.value.lbvh_depth, shared_lbvh_depth);
        atomicMax(info.value.depth, shared_depth);
        atomicAdd(info.value.leaf_count, shared_leaves);
        atomicMax(info.value.largest_leaf, shared_largest);
        atomicAdd(info.value.capped_leaves, shared_capped);
    }
}
