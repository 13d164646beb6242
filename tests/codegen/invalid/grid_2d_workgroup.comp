#version 460
#extension GL_GOOGLE_include_directive : require
// The index from vplkit/dispatch.glsl in a 2D workgroup: linear_thread_index() counts
// gl_LocalInvocationID.x only, so rows of the workgroup would share indices. Codegen must refuse it.
#include "vplkit/dispatch.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) buffer Marks { uint items[]; } marks;

void main() {
    marks.items[linear_thread_index()] = 1u;
}
