#version 460
#extension GL_GOOGLE_include_directive : require
// SMC in a posed scene: where each scene triangle now lies in the BVH (its leaf slot), for
// smc_follow_surfaces.comp. A VPL names its triangle by the scene's index (BvhTriangle.id), and
// a rebuilt BVH orders its leaves anew (the first move's GPU build, or a refit past its cost
// bound), so the slot is looked up after every move: slots[id] = i for the BVH's triangle i.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 2
#include "vplkit/bvh.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 3) writeonly buffer SmcTriangleSlotBuffer { uint items[]; } slots;

layout(push_constant) uniform SmcTriangleSlotsPush {
    uint triangle_count;  // the BVH's triangles
    uint slot_count;      // entries of slots (the scene's triangles)
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= push.triangle_count) {
        return;
    }
    uint id = bvh_triangle(bvh_arrays(), i).id;
    if (id < push.slot_count) {
        slots.items[id] = i;
    }
}
