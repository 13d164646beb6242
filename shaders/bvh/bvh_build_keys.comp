#version 460
#extension GL_GOOGLE_include_directive : require
// GPU BVH build, step 2 (see vplkit/bvh_build.glsl): each triangle's 30-bit Morton code of its
// centroid in the centroid box (Karras 2012, sec. 4), as a sort key, with the triangle's index
// as the value; alpha-tested triangles' keys have kBvhBuildMaskedBit set (bvh_build.glsl). Equal codes are told apart by their sorted position in the hierarchy step
// (Karras 2012: the key concatenated with its index), and the stable sort keeps them in input order.

#include "vplkit/bvh_build.glsl"
#include "vplkit/dispatch.glsl"
#include "vplkit/morton.glsl"
#include "vplkit/ordered_float.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer BvhBuildInputBuffer { BvhTriangle items[]; } input_triangles;
layout(std430, set = 0, binding = 1) readonly buffer BvhBuildInfoBuffer { BvhBuildInfo value; } info;
layout(std430, set = 0, binding = 2) writeonly buffer BvhBuildKeyBuffer { uint64_t items[]; } keys;
layout(std430, set = 0, binding = 3) writeonly buffer BvhBuildOrderBuffer { uint items[]; } order;

layout(push_constant) uniform BvhBuildKeysPush {
    uint triangle_count;
    uvec2 input_triangles_address;  // with kBvhBuildAddressed (bvh_build.glsl)
} push;

BVH_BUILD_GETTER(BvhTriangle, input_triangles, BvhBuildTriangleArray)

void main() {
    uint i = linear_thread_index();
    if (i >= push.triangle_count) {
        return;
    }
    vec3 lo = vec3(ordered_to_float(info.value.centroid_lo[0]), ordered_to_float(info.value.centroid_lo[1]),
                   ordered_to_float(info.value.centroid_lo[2]));
    vec3 hi = vec3(ordered_to_float(info.value.centroid_hi[0]), ordered_to_float(info.value.centroid_hi[1]),
                   ordered_to_float(info.value.centroid_hi[2]));
    BvhTriangle tri = input_triangles_get(i);
    vec3 box_lo, box_hi;
    bvh_build_triangle_box(tri, box_lo, box_hi);
    vec3 center = 0.5 * (box_lo + box_hi);
    uint masked = tri.alpha != 0u ? 1u << kBvhBuildMaskedBit : 0u;
    keys.items[i] = uint64_t(masked | morton_code_30(morton_cell(center, lo, hi)));
    order.items[i] = i;
}
