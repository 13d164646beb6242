#version 460
#extension GL_GOOGLE_include_directive : require
// SMC, Alg. 1 line 4 (the SMC paper sec. 3.2.2), the mailbox test: a VPL stays valid while the camera
// still sees the point it was associated with (its anchor: in the view frustum, on the camera's
// side, and unoccluded from the eye by a BVH ray). smc_invalid_list.comp then lists the others,
// in index order, for smc_revalidate.comp. While geometry stays still, the anchor still sees
// the VPL. After it moved (surfaces_moved), two more rays per VPL: one down its normal must meet
// its own triangle (else the surface left it: the VPL is dead, its light zero, see smc.glsl), and
// the anchor must still see it (a moved object may stand between them).

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 2
#include "vplkit/bvh.glsl"
#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 3) buffer SmcStateBuffer { SmcVpl items[]; } state;
layout(std430, set = 0, binding = 4) writeonly buffer SmcValidBuffer { uint items[]; } valid;
layout(std430, set = 0, binding = 5) readonly buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcValidatePush {
    mat4 view_projection;  // world -> Vulkan clip space
    vec3 camera_position;
    uint budget;
    uint surfaces_moved;   // 1: the geometry moved since the last update
} push;

bool anchor_seen(vec3 a, vec3 na) {
    vec4 clip = push.view_projection * vec4(a, 1.0);
    if (!(clip.w > 0.0) || abs(clip.x) > clip.w || abs(clip.y) > clip.w || clip.z < 0.0 || clip.z > clip.w) {
        return false;
    }
    if (!(dot(na, push.camera_position - a) > 0.0)) {
        return false;
    }
    return !bvh_segment_occluded(a, na, push.camera_position, vec3(0.0), bvh_scene_scale());
}

void main() {
    uint i = linear_thread_index();
    if (i >= push.budget || i >= counters.c.vpl_count) {
        return;
    }
    SmcVpl v = state.items[i];
    if (push.surfaces_moved != 0u && (v.flags & kSmcDead) == 0u) {
        float scale = bvh_scene_scale();
        // The VPL was a hit on its triangle: from just above it, down the normal, within 1e-3 of the scene.
        float reach = 1e-3 * scale;
        vec3 above = offset_ray_origin(v.position, v.normal, scale) + v.normal * reach;
        BvhHit hit = bvh_closest_hit(above, -v.normal, 0.0, 2.0 * reach + length(above - v.position));
        if (hit.id != v.triangle) {
            v.flags |= kSmcDead;
            state.items[i].flags = v.flags;
            state.items[i].radiosity = vec3(0.0);
            state.items[i].choice_radiosity = vec3(0.0);
        }
    }
    bool seen = (v.flags & kSmcDead) == 0u && anchor_seen(v.anchor, v.anchor_normal);
    if (seen && push.surfaces_moved != 0u) {
        seen = !bvh_segment_occluded(v.anchor, v.anchor_normal, v.position, v.normal, bvh_scene_scale());
    }
    valid.items[i] = seen ? 1u : 0u;
}
