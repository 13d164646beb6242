#version 460
#extension GL_GOOGLE_include_directive : require
// One 64-bit sort key per VPL (Morton position code, normal code, id; see morton.glsl),
// paired with the VPL's index as the sort value. Slots past a count the GPU wrote get the
// largest key, so the sort moves them behind every real VPL.

#include "vplkit/vpl.glsl"
#include "vplkit/morton.glsl"
#include "vplkit/ordered_float.glsl"
#include "vplkit/dispatch.glsl"
#include "vplkit/element_count.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer VplBuffer { Vpl items[]; } vpls;
layout(std430, set = 0, binding = 1) readonly buffer VplBoundsBuffer { uint lo[3]; uint hi[3]; } bounds;
layout(std430, set = 0, binding = 2) writeonly buffer KeyBuffer { uint64_t items[]; } keys;
layout(std430, set = 0, binding = 3) writeonly buffer ValueBuffer { uint items[]; } values;
VPLKIT_DECLARE_ELEMENT_COUNT(4)

layout(push_constant) uniform MortonKeysPush {
    uint vpl_count;   // capacity: the VPLs the buffers hold room for
    uint count_word;  // element_count.glsl
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= push.vpl_count) {
        return;
    }
    if (i >= element_count(push.vpl_count, push.count_word)) {
        keys.items[i] = 0xffffffffffffffffUL;
        values.items[i] = i;
        return;
    }
    vec3 lo = vec3(ordered_to_float(bounds.lo[0]), ordered_to_float(bounds.lo[1]), ordered_to_float(bounds.lo[2]));
    vec3 hi = vec3(ordered_to_float(bounds.hi[0]), ordered_to_float(bounds.hi[1]), ordered_to_float(bounds.hi[2]));
    Vpl vpl = vpls.items[i];
    uint morton = morton_code_30(morton_cell(vpl.position, lo, hi));
    keys.items[i] = vpl_sort_key(morton, normal_code_9(vpl.normal), i);
    values.items[i] = i;
}
