#version 460
#extension GL_GOOGLE_include_directive : require
// GPU BVH build, last step, and of a refit (see vplkit/bvh_build.glsl): each kept slot's
// depth-first position, by walking up to the root (a left child follows its parent; a right
// child follows its parent and the left sibling's subtree), and its output node there, in
// bvh.glsl's layout, with the box padded as the host build pads it (vplkit/bvh.hpp).

#include "vplkit/bvh_build.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

struct BvhNode {
    vec3 lo;
    uint index;
    vec3 hi;
    uint meta;
};

layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer BvhNodeArray {
    BvhNode items[];
};

layout(std430, set = 0, binding = 0) readonly buffer BvhBuildNodeBuffer { BvhBuildNode items[]; } nodes;
layout(std430, set = 0, binding = 1) readonly buffer BvhBuildLinkBuffer { BvhBuildLink items[]; } links;
layout(std430, set = 0, binding = 2) buffer BvhBuildInfoBuffer { BvhBuildInfo value; } info;
layout(std430, set = 0, binding = 3) writeonly buffer BvhNodeBuffer { BvhNode items[]; } bvh_nodes;

layout(push_constant) uniform BvhBuildWritePush {
    uint triangle_count;
    uvec2 nodes_address;  // with kBvhBuildAddressed (bvh_build.glsl)
    uvec2 links_address;
    uvec2 bvh_nodes_address;
} push;

BVH_BUILD_GETTER(BvhBuildLink, links, BvhBuildLinkArray)
BVH_BUILD_GETTER(BvhBuildNode, nodes, BvhBuildNodeArray)

void main() {
    uint slot = linear_thread_index();
    if (slot >= 2u * push.triangle_count - 1u) {
        return;
    }
    BvhBuildLink link = links_get(slot);
    if (link.kind == kBvhBuildHidden) {
        return;
    }
    uint position = 0u;
    uint node = slot;
    for (uint step = 0u; step < kBvhBuildMaxWalk && node != 0u; ++step) {
        uint parent = links_get(node).parent;
        uint left = nodes_get(parent).left;
        position += left == node ? 1u : 1u + links_get(left).size;
        node = parent;
    }

    float padding = uintBitsToFloat(info.value.scale) * kBvhBuildBoxPadding;
    BvhBuildNode box = nodes_get(slot);
    BvhNode out_node;
    out_node.lo = box.lo - vec3(padding);
    out_node.hi = box.hi + vec3(padding);
    if (link.kind == kBvhBuildLeaf) {
        out_node.index = link.first;
        out_node.meta = kBvhBuildLeafFlag | link.count;
    } else {
        out_node.index = position + 1u + links_get(box.left).size;
        out_node.meta = link.axis;
    }
    BVH_BUILD_SET(bvh_nodes, BvhNodeArray, position, , out_node);
    if (slot == 0u) {
        info.value.node_count = link.size;
        vec3 m = max(abs(out_node.lo), abs(out_node.hi));
        info.value.scene_scale = max(max(m.x, m.y), max(m.z, kBvhBuildMinScale));
        // Opaque and masked triangles both present: the root splits between them.
        bool split = link.kind == kBvhBuildInterior && link.split_bit == kBvhBuildMaskedBit;
        info.value.masked_root = split ? out_node.index : 0u;
    }
}
