#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Forward light cuts: the kept candidates' and the divergent triangles' indices as two compact
// lists, and how many fell in each level, so the next passes (the subdivision of divergent
// triangles, the splatting) draw only what survived the decimation (the FLC paper sec. 6: the
// divergent buffer feeds an indirect draw). The host zeroes `counts` first.
// Both lists are in triangle index order, the same for every scheduling (an atomic append made
// the draw order, and so the rounding of the additively blended splats, vary): a stable
// compaction. One workgroup walks triangles [first, end) a workgroup-size chunk at a time, one
// prefix sum per chunk for both lists (kept in the low 16 bits, divergent in the high 16: a
// chunk has at most 256 of each), and carries the lists' lengths in `counts` from one dispatch
// to the next. The host keeps each dispatch to 256 chunks, far below lavapipe's loop limit.

#include "vplkit/flc_candidate.glsl"
#include "vplkit/flc_partition.glsl"

layout(local_size_x = 256) in;

#include "vplkit/radix.glsl"

layout(std430, set = 0, binding = 0) readonly buffer FlcCandidateBuffer { FlcCandidate items[]; } candidates;

layout(std430, set = 0, binding = 1) buffer FlcCountBuffer {
    uint kept;           // entries of kept_triangles
    uint divergent;      // entries of divergent_triangles
    uint level_counts[]; // one per level 0..N
} counts;

layout(std430, set = 0, binding = 2) writeonly buffer KeptTriangleBuffer { uint items[]; } kept_triangles;
layout(std430, set = 0, binding = 3) writeonly buffer DivergentTriangleBuffer { uint items[]; } divergent_triangles;

layout(push_constant) uniform FlcCompactPush {
    uint first;  // this dispatch's triangles: [first, end)
    uint end;
} push;

void main() {
    // The earlier dispatches' entries. Every invocation reads them before the loop's barriers,
    // invocation 0 writes them after.
    uint kept = counts.kept;
    uint divergent = counts.divergent;
    // The bounds are uniform, so every invocation reaches the scan's barriers.
    for (uint chunk = push.first; chunk < push.end; chunk += gl_WorkGroupSize.x) {
        uint t = chunk + gl_LocalInvocationID.x;
        int level = t < push.end ? candidates.items[t].level : kFlcDiscarded;
        uint flags = (level >= 0 ? 1u : 0u) | (level == kFlcDivergent ? 0x10000u : 0u);
        uint total;
        uint before = radix_workgroup_exclusive_scan(flags, total);
        if (level >= 0) {
            kept_triangles.items[kept + (before & 0xffffu)] = t;
            atomicAdd(counts.level_counts[level], 1u);  // a count: the same in any order
        } else if (level == kFlcDivergent) {
            divergent_triangles.items[divergent + (before >> 16)] = t;
        }
        kept += total & 0xffffu;
        divergent += total >> 16;
    }
    barrier();
    if (gl_LocalInvocationID.x == 0u) {
        counts.kept = kept;
        counts.divergent = divergent;
    }
}
