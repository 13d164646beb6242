#version 460
#extension GL_GOOGLE_include_directive : require
// Test-only: the area F^k(t, x) = S_k f~^k(d(t, x)) that each VPL candidate of flc_candidates.comp
// stands for at receiver points (0 when discarded), through vplkit/flc_partition.glsl, and the
// support distance d(t, x) (eq. 14).

#include "vplkit/flc_candidate.glsl"
#include "vplkit/flc_partition.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer FlcCandidateBuffer { FlcCandidate items[]; } candidates;
// Point i belongs to candidate i / points_per_candidate; xyz used.
layout(std430, set = 0, binding = 1) readonly buffer PointBuffer { vec4 items[]; } points;

struct CandidateWeight {
    float area_weight;
    float distance;
};

layout(std430, set = 0, binding = 2) writeonly buffer CandidateWeightBuffer { CandidateWeight items[]; } weights;

layout(push_constant) uniform CandidateWeightsPush {
    uint point_count;
    uint points_per_candidate;
    int level_count;
    float s0;
    float d0;
    float mu;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.point_count) {
        return;
    }
    FlcCandidate c = candidates.items[i / push.points_per_candidate];
    float d = flc_support_distance(points.items[i].xyz, c.position, c.normal);
    weights.items[i].distance = d;
    weights.items[i].area_weight =
        c.level >= 0 ? flc_vpl_area_weight(c.level, d, push.level_count, push.s0, push.d0, push.mu) : 0.0;
}
