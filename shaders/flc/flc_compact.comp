#version 460
#extension GL_GOOGLE_include_directive : require
// Forward light cuts: the kept candidates' and the divergent triangles' indices as two compact
// lists, and how many fell in each level, so the next passes (the subdivision of divergent
// triangles, the splatting) draw only what survived the decimation (seed 002 sec. 6: the
// divergent buffer feeds an indirect draw). The host zeroes `counts` first. List order is the
// atomics' order: not deterministic, and nothing downstream depends on it (every VPL splats alone).

#include "vplkit/flc_candidate.glsl"
#include "vplkit/flc_partition.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer FlcCandidateBuffer { FlcCandidate items[]; } candidates;

layout(std430, set = 0, binding = 1) buffer FlcCountBuffer {
    uint kept;           // entries of kept_triangles
    uint divergent;      // entries of divergent_triangles
    uint level_counts[]; // one per level 0..N
} counts;

layout(std430, set = 0, binding = 2) writeonly buffer KeptTriangleBuffer { uint items[]; } kept_triangles;
layout(std430, set = 0, binding = 3) writeonly buffer DivergentTriangleBuffer { uint items[]; } divergent_triangles;

layout(push_constant) uniform FlcCompactPush {
    uint triangle_count;
} push;

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= push.triangle_count) {
        return;
    }
    int level = candidates.items[t].level;
    if (level >= 0) {
        kept_triangles.items[atomicAdd(counts.kept, 1u)] = t;
        atomicAdd(counts.level_counts[level], 1u);
    } else if (level == kFlcDivergent) {
        divergent_triangles.items[atomicAdd(counts.divergent, 1u)] = t;
    }
}
