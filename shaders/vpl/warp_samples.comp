#version 460
#extension GL_GOOGLE_include_directive : require
// Hierarchical warping of a randomized Hammersley point set into texels of the importance map
// (the thesis sec. 4.1, ch. 6): one thread per sample walks from the 1x1 top of the mip chain
// down to the finest level, choosing quadrant by quadrant, vertical half then horizontal half,
// each by the ratio of the halves' sums. The sample lands on a texel with probability
// importance / total, written beside it so a VPL made from it gets flux / (N x pmf).
// An all-zero map gives no samples: `result.count` is 0 and no sample is written.

#include "vplkit/sampling.glsl"
#include "vplkit/dispatch.glsl"

layout(local_size_x = 256, local_size_x_id = 0) in;  // 256 unless specialized

layout(std430, set = 0, binding = 0) readonly buffer ImportanceMipBuffer { float values[]; } mips;
layout(std430, set = 0, binding = 1) writeonly buffer WarpedSampleBuffer { WarpedSample items[]; } samples;
layout(std430, set = 0, binding = 2) writeonly buffer WarpCountBuffer { uint count; } result;

layout(push_constant) uniform WarpSamplesPush {
    uint sample_count;
    uint seed;
    uint levels;      // log2 of the finest level's width
    uint top_offset;  // first float of the 1x1 level in `mips`
} push;

void main() {
    uint i = linear_thread_index();
    float total = mips.values[push.top_offset];
    // "!(total > 0)" also turns away a NaN total.
    bool empty = !(total > 0.0) || isinf(total);
    if (i == 0u) {
        result.count = empty ? 0u : push.sample_count;
    }
    if (empty || i >= push.sample_count) {
        return;
    }

    vec2 u = hammersley_2d(i, push.sample_count, hammersley_rotation(push.seed));
    uvec2 texel = uvec2(0u);
    // Level `level` (width 1 << level in the finest-first layout counted from the top) starts
    // after the levels below it; walk offsets from the top down.
    uint offset = push.top_offset;
    for (uint level = 1u; level <= push.levels; ++level) {
        uint size = 1u << level;
        offset -= size * size;
        uvec2 base = 2u * texel;
        float c00 = mips.values[offset + base.y * size + base.x];
        float c10 = mips.values[offset + base.y * size + base.x + 1u];
        float c01 = mips.values[offset + (base.y + 1u) * size + base.x];
        float c11 = mips.values[offset + (base.y + 1u) * size + base.x + 1u];
        // the thesis ch. 6: vertical half first, then the horizontal quarter within it.
        bool lower = warp_select(u.y, c00 + c10, c01 + c11);
        bool right = lower ? warp_select(u.x, c01, c11) : warp_select(u.x, c00, c10);
        texel = base + uvec2(right ? 1u : 0u, lower ? 1u : 0u);
    }
    uint finest = 1u << push.levels;
    uint index = texel.y * finest + texel.x;
    samples.items[i].texel = index;
    samples.items[i].pmf = warp_select_pmf(mips.values[index], total);
}
