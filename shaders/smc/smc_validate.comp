#version 460
#extension GL_GOOGLE_include_directive : require
// SMC, Alg. 1 line 4 (the SMC paper sec. 3.2.2), the mailbox test: a VPL stays valid while the camera
// still sees the point it was associated with (its anchor: in the view frustum, on the camera's
// side, and unoccluded from the eye by a BVH ray). smc_invalid_list.comp then lists the others,
// in index order, for smc_revalidate.comp. Geometry is static, so the anchor still sees the VPL.

#define VPLKIT_BVH_NODES_BINDING 0
#define VPLKIT_BVH_TRIANGLES_BINDING 1
#define VPLKIT_BVH_ALPHA_BINDING 2
#include "vplkit/bvh.glsl"
#include "smc.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 3) readonly buffer SmcStateBuffer { SmcVpl items[]; } state;
layout(std430, set = 0, binding = 4) writeonly buffer SmcValidBuffer { uint items[]; } valid;
layout(std430, set = 0, binding = 5) readonly buffer SmcCounterBuffer { SmcCounters c; } counters;

layout(push_constant) uniform SmcValidatePush {
    mat4 view_projection;  // world -> Vulkan clip space
    vec3 camera_position;
    uint budget;
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
    valid.items[i] = anchor_seen(v.anchor, v.anchor_normal) ? 1u : 0u;
}
