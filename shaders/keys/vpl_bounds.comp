#version 460
#extension GL_GOOGLE_include_directive : require
// Bounding box of all VPL positions, the frame the Morton codes quantize in.
// The host clears `bounds` first (lo to 0xffffffff, hi to 0), then this reduces each workgroup's
// box in shared memory and merges it into `bounds` with one set of atomics per workgroup.

#include "vplkit/vpl.glsl"
#include "vplkit/ordered_float.glsl"
#include "vplkit/dispatch.glsl"
#include "vplkit/element_count.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer VplBuffer { Vpl items[]; } vpls;
// Ordered-uint encoded box (see ordered_float.glsl); decoded by morton_keys.comp.
layout(std430, set = 0, binding = 1) buffer VplBoundsBuffer { uint lo[3]; uint hi[3]; } bounds;
VPLKIT_DECLARE_ELEMENT_COUNT(2)

layout(push_constant) uniform VplBoundsPush {
    uint vpl_count;   // capacity: the VPLs the buffer holds room for
    uint count_word;  // element_count.glsl
} push;

shared uint shared_lo[3];
shared uint shared_hi[3];

void main() {
    if (gl_LocalInvocationIndex < 3u) {
        shared_lo[gl_LocalInvocationIndex] = 0xffffffffu;
        shared_hi[gl_LocalInvocationIndex] = 0u;
    }
    barrier();

    uint i = linear_thread_index();
    if (i < element_count(push.vpl_count, push.count_word)) {
        vec3 p = vpls.items[i].position;
        // Non-finite positions would make the whole box meaningless; they are left out here
        // (and rejected on the host when VPLs are uploaded).
        if (!any(isnan(p)) && !any(isinf(p))) {
            for (int axis = 0; axis < 3; ++axis) {
                uint key = float_to_ordered(p[axis]);
                atomicMin(shared_lo[axis], key);
                atomicMax(shared_hi[axis], key);
            }
        }
    }
    barrier();

    if (gl_LocalInvocationIndex < 3u) {
        uint axis = gl_LocalInvocationIndex;
        if (shared_lo[axis] <= shared_hi[axis]) {  // this workgroup saw at least one VPL
            atomicMin(bounds.lo[axis], shared_lo[axis]);
            atomicMax(bounds.hi[axis], shared_hi[axis]);
        }
    }
}
