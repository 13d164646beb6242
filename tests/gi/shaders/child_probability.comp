#version 460
#extension GL_GOOGLE_include_directive : require
// Test-only: gi_child_probability (vplkit/gi_bounds.glsl), the sst and hybrid traversals' child
// probability, for weight pairs the host writes: (a_left, d2_left, a_right, d2_right) -> p_left.

#include "vplkit/brdf.glsl"
#include "vplkit/gi_bounds.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer ChildWeights { vec4 items[]; } weights;
layout(std430, set = 0, binding = 1) writeonly buffer ChildProbabilities { float items[]; } probabilities;

layout(push_constant) uniform ChildProbabilityPush {
    uint count;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) {
        return;
    }
    vec4 w = weights.items[i];
    probabilities.items[i] = gi_child_probability(w.x, w.y, w.z, w.w);
}
