#version 460
#extension GL_GOOGLE_include_directive : require
// SMC in a posed scene: each VPL of Y moves with its surface. A VPL is a point of one scene
// triangle (its barycentrics, kept from the ray that found it); after the geometry moved it is
// put at the same barycentric point of that triangle's new pose, its normal the triangle's new
// one on the same side (kSmcFlipped). The turning block of the animated box otherwise left its
// VPLs in the air every frame: dead, replaced at most M_max a frame, the block's faces lit by the
// few VPLs that entered that frame (the image 1.6x IR's error). smc_validate.comp then tests what
// the move changed: whether the spot is still open surface (a VPL now under another surface dies)
// and whether its anchor still sees it. A triangle the BVH no longer holds leaves its VPL dead.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 2
#include "vplkit/bvh.glsl"
#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 3) buffer SmcStateBuffer { SmcVpl items[]; } state;
layout(std430, set = 0, binding = 4) readonly buffer SmcTriangleSlotBuffer { uint items[]; } slots;
layout(std430, set = 0, binding = 5) readonly buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcFollowSurfacesPush {
    uint budget;
    uint triangle_count;  // the BVH's triangles
    uint slot_count;      // entries of slots (the scene's triangles)
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= push.budget || i >= counters.c.vpl_count) {
        return;
    }
    SmcVpl v = state.items[i];
    if ((v.flags & kSmcDead) != 0u) {
        return;
    }
    uint slot = v.triangle < push.slot_count ? slots.items[v.triangle] : kBvhNoHit;
    vec3 position = vec3(0.0), normal = vec3(0.0);
    bool placed = false;
    if (slot < push.triangle_count) {
        BvhTriangle tri = bvh_triangle(bvh_arrays(), slot);
        vec3 winding = cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
        position = (1.0 - v.barycentrics.x - v.barycentrics.y) * tri.v0 + v.barycentrics.x * tri.v1 +
                   v.barycentrics.y * tri.v2;  // as bvh_hit_position
        normal = normalize((v.flags & kSmcFlipped) != 0u ? -winding : winding);
        placed = tri.id == v.triangle && bvh_finite(position) && bvh_finite(normal);
    }
    if (placed) {
        state.items[i].position = position;
        state.items[i].normal = normal;
    } else {
        state.items[i].flags = v.flags | kSmcDead;
        state.items[i].radiosity = vec3(0.0);
        state.items[i].choice_radiosity = vec3(0.0);
    }
}
