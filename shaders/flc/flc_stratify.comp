#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// Forward light cuts, stratified decimation: the level of every regular candidate, drawn with
// Alg. 1's probabilities P(t in L_k) = A / S_k (eq. 3, the FLC paper) but not independently per
// triangle. Independent draws (flc_candidates.comp's Alg. 1) leave each level's count binomial:
// on a closed sphere lit by 16 VPLs of one level a frame's light was 20% off whenever a VPL more
// or less was drawn, though the mean over frames was right. Here each level is a systematic
// sample along `order` (candidates sorted by the Morton code of their centroids, so a run of the
// order is a region of the scene): a level lays its candidates' probabilities end to end on a
// line, starting at a uniform random offset, and keeps the candidates on which an integer falls.
// Every candidate keeps its probability exactly (the offset is uniform), and every run of the
// order, the whole scene included, gets its expected count of the level within one, of the
// probability mass the coarser levels left free there (below).
//
// The levels must stay exclusive (one VPL per triangle, one level per VPL), so they are drawn one
// after the other, coarsest first, each among the candidates no coarser level took, with the
// conditional probability q_k = p_k / (1 - sum_{j>k} p_j): P(t in L_k) = P(t free at k) q_k =
// p_k, since a level's offset is independent of the coarser levels' draws. The mass left free
// varies with the areas of the candidates the coarser levels took, so a finer level's count
// varies a little more (tests/flc/test_flc_stratify.cpp: up to 1% of the finest level's count
// in a region, where independent draws' sd is 1.6%); the coarse levels, few VPLs of large weight
// each, get the exact counts. q_k <= 1 holds for a regular triangle (sum_k p_k <= 1, A <= S~_N).
//
// With the partition's scene_area set, S_k is flc_fitted_level_area's: the scene's area divided by
// a whole number of VPLs, so the whole scene's line of a level has a whole length and the level
// gets exactly that count every frame, each VPL standing for an equal share of the scene's area.
//
// Divergent candidates (flc_subdivide.comp cuts them) and candidates of zero area are left as
// they are; the others get a level or kFlcDiscarded. One workgroup walks `order` [first, end) a
// workgroup-size chunk at a time, one prefix sum per level and chunk, and carries each level's
// offset to the next chunk and, in `carries`, to the next dispatch (the host keeps each dispatch
// to 4096 / levels chunks: lavapipe's loop limit).

#include "vplkit/flc_candidate.glsl"
#include "vplkit/flc_partition.glsl"
#include "vplkit/rng.glsl"

layout(local_size_x = 256) in;

layout(std430, set = 0, binding = 0) buffer FlcCandidateBuffer { FlcCandidate items[]; } candidates;
// Candidate indices, each once, in the order the levels are stratified along.
layout(std430, set = 0, binding = 1) readonly buffer FlcOrderBuffer { uint items[]; } order;
// Each level's offset in [0, 1) where the last dispatch left it.
layout(std430, set = 0, binding = 2) buffer FlcCarryBuffer { float items[]; } carries;

layout(push_constant) uniform FlcStratifyPush {
    uint first;  // this dispatch's positions in `order`: [first, end); first 0 starts the offsets
    uint end;
    uint seed;
    int level_count;
    float s0;
    float mu;
    float scene_area;  // 0: S_k = S_0 mu^k; else flc_fitted_level_area's
} push;

const uint kMaxLevels = 32u;  // stages::kFlcMaxLevels
shared float scan_values[gl_WorkGroupSize.x];
shared float level_offsets[kMaxLevels];

// Inclusive prefix sum over the workgroup in invocation order (Hillis-Steele, log2(size) steps);
// `total` is the whole workgroup's. Every invocation must call it, in uniform control flow.
float workgroup_inclusive_sum(float value, out float total) {
    uint i = gl_LocalInvocationID.x;
    scan_values[i] = value;
    barrier();
    for (uint step = 1u; step < gl_WorkGroupSize.x; step <<= 1u) {
        float before = i >= step ? scan_values[i - step] : 0.0;
        barrier();
        scan_values[i] += before;
        barrier();
    }
    float inclusive = scan_values[i];
    total = scan_values[gl_WorkGroupSize.x - 1u];
    barrier();  // before the next call overwrites the array
    return inclusive;
}

void main() {
    uint lid = gl_LocalInvocationID.x;
    int levels = push.level_count;
    if (lid < uint(levels)) {
        // A uniform offset per level and seed, independent of the other levels'.
        float start = float(pcg_hash(pcg_hash(push.seed) ^ pcg_hash(0x9e3779b9u + lid)) >> 8u) * (1.0 / 16777216.0);
        level_offsets[lid] = push.first == 0u ? start : carries.items[lid];
    }
    barrier();
    // The bounds are uniform, so every invocation reaches the scans' barriers.
    for (uint chunk = push.first; chunk < push.end; chunk += gl_WorkGroupSize.x) {
        uint r = chunk + lid;
        uint t = r < push.end ? order.items[r] : 0u;
        float area = 0.0;
        bool regular = false;
        if (r < push.end) {
            FlcCandidate c = candidates.items[t];
            area = c.area;
            regular = c.level != kFlcDivergent && area > 0.0 && !isinf(area);
        }
        int level = kFlcDiscarded;
        float coarser = 0.0;  // sum of p_j over the levels already drawn (j > k)
        for (int k = levels - 1; k >= 0; --k) {
            float p = regular ? area / flc_fitted_level_area(k, push.s0, push.mu, push.scene_area) : 0.0;
            float q = regular && level == kFlcDiscarded ? clamp(p / max(1.0 - coarser, 1e-30), 0.0, 1.0) : 0.0;
            coarser += p;
            float offset = level_offsets[k];  // read before the scan's barriers, written after them
            float total;
            float x = offset + workgroup_inclusive_sum(q, total) - q;  // where q's segment starts
            if (q > 0.0 && ceil(x) < x + q) {
                level = k;  // an integer falls in [x, x + q)
            }
            if (lid == 0u) {
                level_offsets[k] = fract(offset + total);
            }
        }
        if (regular) {
            candidates.items[t].level = level;
        }
    }
    barrier();
    if (lid < uint(levels)) {
        carries.items[lid] = level_offsets[lid];
    }
}
