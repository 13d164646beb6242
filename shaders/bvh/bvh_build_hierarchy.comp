#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// GPU BVH build, step 4 (see vplkit/bvh_build.glsl): the Karras tree over the sorted Morton
// codes, one thread per internal node, none waiting for another (Karras 2012, sec. 4 and
// Fig. 4): the node's direction, the other end of its range by an exponential then a binary
// search, its split by a binary search on the common prefix length. Threads past the internal
// nodes set up the leaf slots.

#include "vplkit/bvh_build.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer BvhBuildKeyBuffer { uint64_t items[]; } keys;
layout(std430, set = 0, binding = 1) writeonly buffer BvhBuildNodeBuffer { BvhBuildNode items[]; } nodes;
layout(std430, set = 0, binding = 2) writeonly buffer BvhBuildLinkBuffer { BvhBuildLink items[]; } links;

layout(push_constant) uniform BvhBuildHierarchyPush {
    uint triangle_count;
    uvec2 nodes_address;  // with kBvhBuildAddressed (bvh_build.glsl)
    uvec2 links_address;
} push;

// Karras 2012's delta(i, j): the length of the common prefix of sorted keys i and j, each
// key followed by its 32-bit position so that no two are equal; -1 for j outside [0, n).
int prefix_length(int i, int j) {
    if (j < 0 || j >= int(push.triangle_count)) {
        return -1;
    }
    uint a = uint(keys.items[i]);
    uint b = uint(keys.items[j]);
    if (a != b) {
        return 31 - findMSB(a ^ b);
    }
    return 32 + 31 - findMSB(uint(i ^ j));
}

void main() {
    uint slot = linear_thread_index();
    uint n = push.triangle_count;
    if (slot >= 2u * n - 1u) {
        return;
    }
    uint leaf_base = n - 1u;
    if (slot >= leaf_base) {
        // The leaf of sorted triangle k (its parent is written by the parent's thread).
        BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .first, slot - leaf_base);
        BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .count, 1u);
        BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .axis, 0u);
        BVH_BUILD_SET(nodes, BvhBuildNodeArray, slot, .left, kBvhBuildNone);
        BVH_BUILD_SET(nodes, BvhBuildNodeArray, slot, .right, kBvhBuildNone);
        if (slot == 0u) {
            BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .parent, kBvhBuildNone);  // n = 1: the leaf is the root
        }
        return;
    }

    int i = int(slot);
    // Direction of the range: towards the neighbour with the longer common prefix.
    int d = prefix_length(i, i + 1) > prefix_length(i, i - 1) ? 1 : -1;
    int delta_min = prefix_length(i, i - d);
    // Upper bound of the range length, then the length itself.
    int length_max = 2;
    while (prefix_length(i, i + length_max * d) > delta_min) {
        length_max *= 2;
    }
    int length = 0;
    for (int step = length_max / 2; step >= 1; step /= 2) {
        if (prefix_length(i, i + (length + step) * d) > delta_min) {
            length += step;
        }
    }
    int j = i + length * d;
    // The split: the last position that shares more than the node's prefix with i.
    int delta_node = prefix_length(i, j);
    int split = 0;
    int step = length;
    do {
        step = (step + 1) >> 1;
        if (prefix_length(i, i + (split + step) * d) > delta_node) {
            split += step;
        }
    } while (step > 1);
    int gamma = i + split * d + min(d, 0);

    uint first = uint(min(i, j));
    uint last = uint(max(i, j));
    uint left = first == uint(gamma) ? leaf_base + uint(gamma) : uint(gamma);
    uint right = last == uint(gamma + 1) ? leaf_base + uint(gamma + 1) : uint(gamma + 1);
    BVH_BUILD_SET(nodes, BvhBuildNodeArray, slot, .left, left);
    BVH_BUILD_SET(nodes, BvhBuildNodeArray, slot, .right, right);
    BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .first, first);
    BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .count, last - first + 1u);
    // The split bit: x in the highest bit of each Morton triple, then y, then z (morton.glsl);
    // the left child holds the 0s, the lower coordinates along that axis. Positions only (equal
    // codes) or the masked bit: any axis.
    uint axis = 0u;
    uint split_bit = kBvhBuildNone;
    if (delta_node < 32) {
        split_bit = uint(31 - delta_node);
        axis = 2u - split_bit % 3u;
    }
    BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .axis, axis);
    BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .split_bit, split_bit);
    BVH_BUILD_SET(links, BvhBuildLinkArray, left, .parent, slot);
    BVH_BUILD_SET(links, BvhBuildLinkArray, right, .parent, slot);
    if (slot == 0u) {
        BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .parent, kBvhBuildNone);
    }
}
