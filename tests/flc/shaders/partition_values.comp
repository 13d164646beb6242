#version 460
#extension GL_GOOGLE_include_directive : require
// Test-only: f~^k(d) and F^k(d) = S_k f~^k(d) of vplkit/flc_partition.glsl for every level k at
// the distances the host gives, so the host can compare them with the double reference.

#include "vplkit/flc_partition.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer DistanceBuffer { float items[]; } distances;

struct PartitionValue {
    float weight;       // f~^k(d)
    float area_weight;  // S_k f~^k(d)
};

// [distance index * level_count + k]
layout(std430, set = 0, binding = 1) writeonly buffer PartitionValueBuffer { PartitionValue items[]; } values;

layout(push_constant) uniform PartitionValuesPush {
    uint distance_count;
    int level_count;
    float s0;
    float d0;
    float mu;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.distance_count * uint(push.level_count)) {
        return;
    }
    int k = int(i % uint(push.level_count));
    float d = distances.items[i / uint(push.level_count)];
    values.items[i].weight = flc_partition_weight(k, d, push.level_count, push.d0, push.mu);
    values.items[i].area_weight = flc_vpl_area_weight(k, d, push.level_count, push.s0, push.d0, push.mu);
}
