#version 460
#extension GL_GOOGLE_include_directive : require
// Test shader: rays that start on the scene's own surfaces, the way every later stage starts
// them. Each query names a stored triangle and a point on it (barycentrics); the shader forms
// the point with bvh_hit_position, moves it off the surface with offset_ray_origin along the
// triangle's geometric normal (or against it), and traces the closest hit from there.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 4
#include "vplkit/bvh.glsl"

layout(local_size_x = 64, local_size_x_id = 0) in;  // 64 unless specialized

struct SurfaceQuery {
    vec2 barycentrics;  // of v1 and v2 on the triangle
    uint triangle;      // index into bvh_triangles (leaf order)
    float side;         // +1: leave on the side the normal points to; -1: the other side
    vec3 direction;
    float tmax;
};

struct SurfaceResult {
    vec3 origin;  // the offset origin the ray started from
    float scale;  // bvh_scene_scale()
    BvhHit hit;
};

layout(std430, set = 0, binding = 2) readonly buffer SurfaceQueryBuffer { SurfaceQuery items[]; } queries;
layout(std430, set = 0, binding = 3) writeonly buffer SurfaceResultBuffer { SurfaceResult items[]; } results;

layout(push_constant) uniform SurfaceRaysPush {
    uint count;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) {
        return;
    }
    SurfaceQuery q = queries.items[i];
    BvhHit at = bvh_no_hit(0.0);
    at.triangle = q.triangle;
    at.barycentrics = q.barycentrics;
    vec3 p = bvh_hit_position(at);
    vec3 n = q.side * bvh_triangle_normal(q.triangle);
    float scale = bvh_scene_scale();
    vec3 origin = offset_ray_origin(p, n, scale);
    results.items[i].origin = origin;
    results.items[i].scale = scale;
    results.items[i].hit = bvh_closest_hit(origin, q.direction, 0.0, q.tmax);
}
