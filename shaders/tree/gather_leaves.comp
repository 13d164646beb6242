#version 460
#extension GL_GOOGLE_include_directive : require
// The light trees' leaf array: the VPLs in sorted-key order (the sort moved indices, not whole
// VPLs; the thesis ch. 6 "VPL sorting"), padded to a power of two with bogus leaves.
// A bogus leaf is all zero: zero flux, so zero intensity. Tree builders tell bogus leaves by
// their index (>= count), never by their data, so they never take part in bounds.

#include "vplkit/vpl.glsl"
#include "vplkit/dispatch.glsl"
#include "vplkit/element_count.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer VplBuffer { Vpl items[]; } vpls;
layout(std430, set = 0, binding = 1) readonly buffer SortValueBuffer { uint items[]; } order;
layout(std430, set = 0, binding = 2) writeonly buffer LeafBuffer { Vpl items[]; } leaves;
VPLKIT_DECLARE_ELEMENT_COUNT(3)

layout(push_constant) uniform GatherLeavesPush {
    uint count;       // real VPLs, or the capacity when count_word names the GPU's count
    uint leaf_count;  // count rounded up to a power of two
    uint count_word;  // element_count.glsl
} push;

void main() {
    uint i = linear_thread_index();
    if (i >= push.leaf_count) {
        return;
    }
    if (i < element_count(push.count, push.count_word)) {
        leaves.items[i] = vpls.items[order.items[i]];
    } else {
        leaves.items[i] = Vpl(vec3(0.0), vec3(0.0), vec3(0.0));
    }
}
