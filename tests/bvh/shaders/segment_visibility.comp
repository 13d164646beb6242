#version 460
#extension GL_GOOGLE_include_directive : require
// Test shader: bvh_segment_occluded between two points on the scene's surfaces (or a surface
// point and a free point, like a point light), the way shading stages query visibility.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 4
#include "vplkit/bvh.glsl"

layout(local_size_x = 64, local_size_x_id = 0) in;  // 64 unless specialized

struct SegmentQuery {
    vec2 p_barycentrics;
    uint p_triangle;      // index into bvh_triangles (leaf order)
    uint q_triangle;      // kBvhNoHit: q is q_point, not on a surface
    vec2 q_barycentrics;
    float p_side;         // +1 / -1: the side of p's geometric normal the segment leaves on
    float q_side;
    vec3 q_point;
};

layout(std430, set = 0, binding = 2) readonly buffer SegmentQueryBuffer { SegmentQuery items[]; } queries;
layout(std430, set = 0, binding = 3) writeonly buffer SegmentOcclusionBuffer { uint items[]; } occluded;

layout(push_constant) uniform SegmentVisibilityPush {
    uint count;
} push;

vec3 surface_point(uint triangle, vec2 barycentrics) {
    BvhHit at = bvh_no_hit(0.0);
    at.triangle = triangle;
    at.barycentrics = barycentrics;
    return bvh_hit_position(at);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) {
        return;
    }
    SegmentQuery s = queries.items[i];
    vec3 p = surface_point(s.p_triangle, s.p_barycentrics);
    vec3 np = s.p_side * bvh_triangle_normal(s.p_triangle);
    vec3 q = s.q_point;
    vec3 nq = vec3(0.0);
    if (s.q_triangle != kBvhNoHit) {
        q = surface_point(s.q_triangle, s.q_barycentrics);
        nq = s.q_side * bvh_triangle_normal(s.q_triangle);
    }
    occluded.items[i] = bvh_segment_occluded(p, np, q, nq, bvh_scene_scale()) ? 1u : 0u;
}
