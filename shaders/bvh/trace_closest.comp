#version 460
#extension GL_GOOGLE_include_directive : require
// Closest hit of each ray in a batch (see vplkit/bvh.glsl): for tests, benchmarks, and any
// stage that wants first hits as a buffer rather than inside its own shader.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 4
#include "vplkit/bvh.glsl"
#include "vplkit/dispatch.glsl"

// Small groups: rays diverge, and a group waits for its slowest ray.
layout(local_size_x = 64, local_size_x_id = 0) in;  // 64 unless specialized

layout(std430, set = 0, binding = 2) readonly buffer BvhRayBuffer { BvhRay items[]; } rays;
layout(std430, set = 0, binding = 3) writeonly buffer BvhHitBuffer { BvhHit items[]; } hits;

layout(push_constant) uniform TraceClosestPush {
    uint ray_count;
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= push.ray_count) {
        return;
    }
    hits.items[i] = bvh_closest_hit(rays.items[i]);
}
