#version 460
#extension GL_GOOGLE_include_directive : require
// GPU BVH build, step 6, and the first step of a refit (see vplkit/bvh_build.glsl): each output
// leaf copies its triangles into leaf order and takes the box of their vertices.

#include "vplkit/bvh_build.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer BvhBuildInputBuffer { BvhTriangle items[]; } input_triangles;
layout(std430, set = 0, binding = 1) readonly buffer BvhBuildOrderBuffer { uint items[]; } order;
layout(std430, set = 0, binding = 2) buffer BvhBuildNodeBuffer { BvhBuildNode items[]; } nodes;
layout(std430, set = 0, binding = 3) buffer BvhBuildLinkBuffer { BvhBuildLink items[]; } links;
layout(std430, set = 0, binding = 4) writeonly buffer BvhBuildTriangleBuffer { BvhTriangle items[]; } triangles;

layout(push_constant) uniform BvhBuildLeavesPush {
    uint triangle_count;
    uvec2 input_triangles_address;  // with kBvhBuildAddressed (bvh_build.glsl)
    uvec2 nodes_address;
    uvec2 links_address;
    uvec2 triangles_address;
} push;

BVH_BUILD_GETTER(BvhTriangle, input_triangles, BvhBuildTriangleArray)
BVH_BUILD_GETTER(BvhBuildLink, links, BvhBuildLinkArray)

void main() {
    uint slot = linear_thread_index();
    if (slot >= 2u * push.triangle_count - 1u || links_get(slot).kind != kBvhBuildLeaf) {
        return;
    }
    uint first = links_get(slot).first;
    uint end = first + links_get(slot).count;
    vec3 lo = vec3(3.4028234663852886e38);
    vec3 hi = vec3(-3.4028234663852886e38);
    for (uint k = first; k < end; ++k) {
        BvhTriangle tri = input_triangles_get(order.items[k]);
        BVH_BUILD_SET(triangles, BvhBuildTriangleArray, k, , tri);
        vec3 tri_lo, tri_hi;
        bvh_build_triangle_box(tri, tri_lo, tri_hi);
        lo = min(lo, tri_lo);
        hi = max(hi, tri_hi);
    }
    BVH_BUILD_SET(nodes, BvhBuildNodeArray, slot, .lo, lo);
    BVH_BUILD_SET(nodes, BvhBuildNodeArray, slot, .hi, hi);
    BVH_BUILD_SET(links, BvhBuildLinkArray, slot, .size, 1u);
}
