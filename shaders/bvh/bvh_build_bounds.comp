#version 460
#extension GL_GOOGLE_include_directive : require
// GPU BVH build, step 1 (see vplkit/bvh_build.glsl): the box of the triangle centroids, which
// the Morton codes quantize in, and the largest coordinate magnitude, which the box padding is
// relative to (vplkit/bvh.hpp). The host clears both first (an empty box, scale 0); each
// workgroup reduces in shared memory and merges with one set of atomics (no barrier in
// divergent flow).

#include "vplkit/bvh_build.glsl"
#include "vplkit/dispatch.glsl"
#include "vplkit/ordered_float.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer BvhBuildInputBuffer { BvhTriangle items[]; } input_triangles;
layout(std430, set = 0, binding = 1) buffer BvhBuildInfoBuffer { BvhBuildInfo value; } info;

layout(push_constant) uniform BvhBuildBoundsPush {
    uint triangle_count;
    uvec2 input_triangles_address;  // with kBvhBuildAddressed (bvh_build.glsl)
} push;

BVH_BUILD_GETTER(BvhTriangle, input_triangles, BvhBuildTriangleArray)

shared uint shared_lo[3];
shared uint shared_hi[3];
shared uint shared_scale;

void main() {
    if (gl_LocalInvocationIndex < 3u) {
        shared_lo[gl_LocalInvocationIndex] = 0xffffffffu;
        shared_hi[gl_LocalInvocationIndex] = 0u;
    }
    if (gl_LocalInvocationIndex == 0u) {
        shared_scale = 0u;
    }
    barrier();

    uint i = linear_thread_index();
    if (i < push.triangle_count) {
        vec3 lo, hi;
        bvh_build_triangle_box(input_triangles_get(i), lo, hi);
        // As the host build: the centroid is the box centre.
        vec3 center = 0.5 * (lo + hi);
        for (int axis = 0; axis < 3; ++axis) {
            uint key = float_to_ordered(center[axis]);
            atomicMin(shared_lo[axis], key);
            atomicMax(shared_hi[axis], key);
        }
        vec3 m = max(abs(lo), abs(hi));
        atomicMax(shared_scale, floatBitsToUint(max(max(m.x, m.y), m.z)));
    }
    barrier();

    if (gl_LocalInvocationIndex < 3u) {
        uint axis = gl_LocalInvocationIndex;
        if (shared_lo[axis] <= shared_hi[axis]) {
            atomicMin(info.value.centroid_lo[axis], shared_lo[axis]);
            atomicMax(info.value.centroid_hi[axis], shared_hi[axis]);
        }
    }
    if (gl_LocalInvocationIndex == 0u) {
        atomicMax(info.value.scale, shared_scale);
    }
}
