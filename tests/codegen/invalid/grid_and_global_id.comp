#version 460
#extension GL_GOOGLE_include_directive : require
// Half converted: the index from vplkit/dispatch.glsl, but gl_GlobalInvocationID read too (in a
// grid folded into rows it repeats row 0's ids). Codegen must refuse it.
#include "vplkit/dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Marks { uint items[]; } marks;

void main() {
    uint i = linear_thread_index();
    marks.items[i] = gl_GlobalInvocationID.x;
}
